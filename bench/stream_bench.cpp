// A long history through specimen D as `rheo simulate` runs it (#28): a 1e7-row CSV (a two-sine
// displacement, 1.5 Hz 2 mm plus 23 Hz 0.1 mm, sampled at 10 kHz, written as a rig writes it:
// time shortest, displacement to 1 nm), read, simulated and written as CSV by stream_history,
// in process. The input is generated on the first run into $TMPDIR/rheo-bench-history/ (about
// 190 MB) with history.rheo beside it, and kept there for the whole-process measurement of
// docs/performance.md (`/usr/bin/time -v build/rheo simulate $TMPDIR/rheo-bench-history/history.rheo`).
// Reported: time per run, and samples and bytes per second.
#include "bench_support.hpp"
#include "lang/frontend.hpp"
#include "runtime/io/history_writer.hpp"
#include "runtime/io/output_file.hpp"
#include "runtime/protocols/stream_history.hpp"

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>

namespace {

using namespace rheo;
namespace fs = std::filesystem;

constexpr long kRows = 10'000'000;

// The directory holding history.csv and history.rheo, made once.
fs::path history_directory() {
  const fs::path dir = fs::temp_directory_path() / "rheo-bench-history";
  const fs::path csv = dir / "history.csv", model = dir / "history.rheo";
  if (fs::exists(model) && fs::exists(csv)) return dir;
  fs::create_directories(dir);
  {
    std::FILE* out = std::fopen((dir / "history.tmp").c_str(), "wb");
    if (!out) throw std::runtime_error("cannot write " + (dir / "history.tmp").string());
    std::fputs("time [s],displacement [mm]\n", out);
    fmt::memory_buffer text;
    for (long k = 0; k < kRows; ++k) {
      const double t = static_cast<double>(k) / 10000.0;
      const double u = 2.0 * std::sin(2 * std::numbers::pi * 1.5 * t) + 0.1 * std::sin(2 * std::numbers::pi * 23.0 * t);
      fmt::format_to(std::back_inserter(text), "{},{:.6f}\n", t, u);
      if (text.size() > (1 << 20)) std::fwrite(text.data(), 1, text.size(), out), text.clear();
    }
    std::fwrite(text.data(), 1, text.size(), out);
    std::fclose(out);
    fs::rename(dir / "history.tmp", csv);
  }
  std::ifstream specimen(std::string(RHEO_EXAMPLES_DIR) + "/specimen_d.rheo");
  std::string line, source;
  bool in_model = false;
  while (std::getline(specimen, line)) {  // the model block of the example, then a history protocol
    in_model = in_model || line.rfind("model ", 0) == 0;
    if (in_model) source += line + "\n";
    if (in_model && line == "}") break;
  }
  std::ofstream(model) << source << "simulate {\n  history file = \"history.csv\"\n  output \"out.csv\"\n}\n";
  return dir;
}

void BM_SpecimenD_History_1e7Rows_CsvInOut(benchmark::State& state) {
  const fs::path dir = history_directory();
  const lang::Program program = lang::load_program((dir / "history.rheo").string());
  const runtime::Network network = runtime::Network::compile(*program.find_model("specimen_d"));
  const lang::Protocol& protocol = program.simulations.at(0).protocols.at(0);
  std::uint64_t samples = 0;
  for (auto _ : state) {
    runtime::PendingOutput out((dir / "out.csv").string());
    runtime::HistoryCsvWriter writer(out);
    samples += runtime::stream_history(network, protocol, (dir / "history.rheo").string(), writer).samples;
    writer.finish();
    out.commit();
  }
  state.counters["samples_per_s"] = benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kIsRate);
  state.counters["input_MB_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * static_cast<double>(fs::file_size(dir / "history.csv")) / 1e6, benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_SpecimenD_History_1e7Rows_CsvInOut)->Unit(benchmark::kMillisecond)->Iterations(1);
