// A `history` protocol streamed (protocols/stream_history.hpp) against the same protocol run
// whole (run_protocol): the same samples bit for bit over many pieces, with sub-steps, element
// outputs and a relaxed start away from rest; faults in the file reported as whole-file
// reading reports them, before a failure of the simulation; files the stream does not take
// read whole. And a spring's force k u checked sample by sample on a history many times the
// stream's block, in blocks never longer than kBlockSamples.
#include "runtime/protocols/stream_history.hpp"

#include "lang/frontend.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/io/output.hpp"
#include "runtime/protocols/run_protocols.hpp"
#include "runtime/protocols/solver_choice.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace stream_history_test {

using namespace rheo;
namespace fs = std::filesystem;

namespace {

// Collects what a stream hands over.
class Collect : public runtime::HistorySink {
 public:
  runtime::History history;
  runtime::ResultHeader header;
  std::size_t pieces = 0, largest_piece = 0, restarts = 0;

  void begin(const runtime::ResultHeader& h, const std::vector<std::string>& paths) override {
    header = h;
    history = runtime::History{};
    history.element_paths = paths;
    history.element_force.assign(paths.size(), {});
    history.element_elongation.assign(paths.size(), {});
  }
  void write(const runtime::History& piece) override {
    ++pieces;
    largest_piece = std::max(largest_piece, piece.time.size());
    auto add = [](std::vector<double>& to, const std::vector<double>& from) { to.insert(to.end(), from.begin(), from.end()); };
    add(history.time, piece.time), add(history.displacement, piece.displacement), add(history.force, piece.force);
    for (std::size_t i = 0; i < piece.element_paths.size(); ++i)
      add(history.element_force[i], piece.element_force[i]), add(history.element_elongation[i], piece.element_elongation[i]);
  }
  void restart() override { ++restarts; }
};

bool bitwise(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / fmt::format("rheo-stream-history-{}", ::getpid());
  fs::create_directories(dir);
  return dir;
}

struct Case {
  lang::Program program;
  const lang::Protocol& protocol() const { return program.simulations.at(0).protocols.at(0); }
  runtime::Network network() const { return runtime::Network::compile(*program.find_model(program.simulations.at(0).model)); }
};

Case program(const std::string& model, const std::string& protocol) {
  const fs::path source = scratch() / "m.rheo";
  return {lang::compile_source(source.string(), model + "\nsimulate {\n  " + protocol + "\n}\n")};
}

const char* kSpecimenD = R"(model d {
  yeoh     rubber (D10 = 389.4253 N/mm, D20 = -2.1094 N/mm^3, D30 = 0.0786 N/mm^5)
  maxwell  m1 (k = 61.476 N/mm, tau = 0.004335 s)
  friction f1 (k = 1016.6 N/mm, uy = 101.58 um)
  friction f2 (k = 301.04 N/mm, uy = 42.256 um)
  series s { spring k3 (k = 300 N/mm)
    parallel p { dashpot c (c = 2 N*s/mm)
      friction f3 (k = 80 N/mm, uy = 30 um) } }
})";

// A two-sine history from displacement 0.3 mm (away from rest), ROWS rows, with a pause in its
// sampling (the step length changes) and comment lines.
void write_history(const fs::path& path, int rows) {
  std::ofstream out(path);
  out << "# rig 4\ntime [ms],displacement [um]\n";
  double t = 2.0;
  for (int k = 0; k < rows; ++k) {
    t += k % 5000 == 4999 ? 0.35 : 0.1;
    if (k == 1000) out << "# the rig paused\n";
    out << fmt::format("{},{}\n", t, 300.0 + 2000.0 * std::sin(0.0094 * t) + 100.0 * std::sin(0.144 * t));
  }
}


// Runs C's protocol whole and streamed and checks they agree bit for bit (samples, element
// outputs, header, notes), the stream in more than MIN_PIECES pieces of at most kBlockSamples;
// the whole run's result.
runtime::ProtocolResult check_streamed_is_whole(const Case& c, std::size_t min_pieces) {
  const runtime::Network network = c.network();
  REQUIRE(runtime::streams(c.protocol()));
  const runtime::ProtocolResult whole = runtime::run_protocol(network, c.protocol(), (scratch() / "m.rheo").string());
  const runtime::History& w = std::get<runtime::History>(whole.data);
  Collect streamed;
  const runtime::StreamedHistory run = runtime::stream_history(network, c.protocol(), (scratch() / "m.rheo").string(), streamed);
  const runtime::History& s = streamed.history;
  CHECK(run.samples == w.time.size());
  CHECK(streamed.restarts == 0);
  CHECK(streamed.pieces > min_pieces);
  CHECK(streamed.largest_piece == std::min(runtime::kBlockSamples, w.time.size()));
  CHECK(run.header.protocol == whole.header.protocol);
  CHECK(run.notes == whole.notes);
  CHECK(bitwise(s.time, w.time));
  CHECK(bitwise(s.displacement, w.displacement));
  CHECK(bitwise(s.force, w.force));
  CHECK(s.element_paths == w.element_paths);
  for (std::size_t i = 0; i < w.element_paths.size(); ++i) {
    CHECK(bitwise(s.element_force[i], w.element_force[i]));
    CHECK(bitwise(s.element_elongation[i], w.element_elongation[i]));
  }
  CHECK(runtime::history_csv(run.header, s) == runtime::history_csv(whole.header, w));
  return whole;
}
}  // namespace

TEST_CASE("streamed and whole runs of a history give the same samples bit for bit over many pieces") {
  const fs::path csv = scratch() / "long.csv";
  write_history(csv, 60000);
  REQUIRE(fs::file_size(csv) > (std::size_t{1} << 20));  // two pieces of the stream's 1 MiB block
  for (const std::string settings : {"", ", substeps = 3, elements = all"}) {
    CAPTURE(settings);
    const runtime::ProtocolResult whole = check_streamed_is_whole(program(kSpecimenD, fmt::format("history file = \"long.csv\"{}", settings)), 10);
    const runtime::History& w = std::get<runtime::History>(whole.data);
    CHECK(w.displacement.front() ==
          doctest::Approx(0.3 + 2.0 * std::sin(0.0094 * 2.1) + 0.1 * std::sin(0.144 * 2.1)).scale(0.0));  // relaxed away from rest
  }
}

TEST_CASE("a history many blocks long streams in blocks of kBlockSamples: a spring's force is k u at every sample") {
  const fs::path csv = scratch() / "spring.csv";
  {
    std::ofstream out(csv);
    out << "time [s],displacement [mm]\n";
    for (int k = 0; k < 300000; ++k) out << fmt::format("{},{}\n", k * 1e-3, std::sin(k * 1e-3) + 0.5 * std::sin(k * 0.37));
  }
  const Case c = program("model m { spring s (k = 123.5 N/mm) }", "history file = \"spring.csv\", substeps = 2");
  Collect streamed;
  const runtime::StreamedHistory run = runtime::stream_history(c.network(), c.protocol(), (scratch() / "m.rheo").string(), streamed);
  REQUIRE(run.samples == 2 * 300000 - 1);
  CHECK(streamed.largest_piece <= runtime::kBlockSamples);
  const runtime::History& h = streamed.history;
  std::size_t wrong = 0;
  for (std::size_t j = 0; j < h.time.size(); ++j) {
    const double k = static_cast<double>(j / 2) * 1e-3 + (j % 2 ? 0.5e-3 : 0.0);  // sub-samples halve each interval
    wrong += std::abs(h.time[j] - k) > 1e-9 || h.force[j] != 123.5 * h.displacement[j];
  }
  CHECK(wrong == 0);
}

TEST_CASE("a fault late in the file is reported at its row and column after pieces were written, before a failure of the simulation") {
  const fs::path csv = scratch() / "late.csv";
  {
    std::ofstream out(csv);
    out << "time [s],displacement [mm]\n";
    for (int k = 0; k < 150000; ++k) out << (k == 140000 ? std::string("14,x\n") : fmt::format("{},{}\n", k * 1e-4, 5.0 + std::sin(k * 1e-3)));
  }
  const std::string message = "late.csv:140002:4: error: 'x' is not a number (column 'displacement'); write a number such as 0.25 or 1e-3";
  {
    const Case c = program("model m { spring s (k = 1 N/mm) }", "history file = \"late.csv\"");
    Collect streamed;
    CHECK_THROWS_WITH_AS(runtime::stream_history(c.network(), c.protocol(), (scratch() / "m.rheo").string(), streamed),
                         doctest::Contains(message.c_str()), runtime::DataError);
    CHECK(streamed.pieces > 0);  // provisional: the caller discards them
    CHECK_THROWS_WITH_AS(runtime::run_protocol(c.network(), c.protocol(), (scratch() / "m.rheo").string()), doctest::Contains(message.c_str()),
                         runtime::DataError);
  }
  // A chain whose yeoh spring cannot carry the relaxed start at 5 mm fails at the first sample;
  // whole-file reading would have reported the file's fault first, and so does the stream.
  const Case c = program("model m { series c { spring k (k = 1000 N/mm)\n yeoh y (D10 = 10 N/mm, D20 = -5 N/mm^3, D30 = 0.1 N/mm^5) } }",
                         "history file = \"late.csv\"");
  Collect streamed;
  CHECK_THROWS_WITH_AS(runtime::stream_history(c.network(), c.protocol(), (scratch() / "m.rheo").string(), streamed),
                       doctest::Contains(message.c_str()), runtime::DataError);
  std::ofstream(scratch() / "short.csv") << "time [s],displacement [mm]\n0,5\n1,6\n";
  const Case sound = program("model m { series c { spring k (k = 1000 N/mm)\n yeoh y (D10 = 10 N/mm, D20 = -5 N/mm^3, D30 = 0.1 N/mm^5) } }",
                             "history file = \"short.csv\"");
  CHECK_THROWS_WITH_AS(runtime::stream_history(sound.network(), sound.protocol(), (scratch() / "m.rheo").string(), streamed),
                       doctest::Contains("the relaxed start needs"), runtime::ModelError);
}

TEST_CASE("a UTF-16 history is read whole and written as one piece, with the whole run's results") {
  const std::string text = "time [s],displacement [mm]\n0,0\n0.5,1\n1,0\n";
  std::string utf16 = "\xFF\xFE";
  for (char ch : text) utf16 += ch, utf16 += '\0';
  std::ofstream(scratch() / "utf16.csv", std::ios::binary) << utf16;
  const Case c = program("model m { maxwell m1 (k = 10 N/mm, tau = 0.2 s) }", "history file = \"utf16.csv\"");
  Collect streamed;
  const runtime::StreamedHistory run = runtime::stream_history(c.network(), c.protocol(), (scratch() / "m.rheo").string(), streamed);
  const runtime::ProtocolResult whole = runtime::run_protocol(c.network(), c.protocol(), (scratch() / "m.rheo").string());
  CHECK(streamed.restarts == 1);
  CHECK(streamed.pieces == 1);
  CHECK(run.samples == 3);
  CHECK(bitwise(streamed.history.force, std::get<runtime::History>(whole.data).force));
  CHECK(streamed.history.force[1] == doctest::Approx(10.0 * 0.2 * 2.0 * (1.0 - std::exp(-0.5 / 0.2))).epsilon(1e-12));  // k tau v (1 - e^-t/tau)
}

TEST_CASE("history protocols stream, on either integrator") {
  CHECK(runtime::streams(program("model m { spring s (k = 1 N/mm) }", "history file = \"x.csv\"").protocol()));
  CHECK(runtime::streams(program("model m { spring s (k = 1 N/mm) }", "history file = \"x.csv\", solver = sundials").protocol()));
  CHECK_FALSE(runtime::streams(program("model m { spring s (k = 1 N/mm) }", "step amplitude = 1 mm, duration = 1 s").protocol()));
}

// On IDA (`auto` takes it for a network with an inerter) the stream holds the last samples, not
// the drive, and reads the file once first for the drive's reach and duration, which set IDA's
// tolerances: the samples are the whole run's bit for bit, over pieces, with sub-steps, element
// outputs, a relaxed start away from rest and a slider that slips.
TEST_CASE("a history on IDA streams with the whole run's samples bit for bit") {
  const fs::path csv = scratch() / "ida.csv";
  write_history(csv, 9000);
  const std::string hydro = R"(model h {
  spring rubber (k = 800 N/mm)
  maxwell visco (k = 150 N/mm, tau = 3 ms)
  series fluid { slider cap (fy = 60 N)  spring k1 (k = 600 N/mm)
    parallel y { inerter column (b = 40 kg)  dashpot channel (c = 3 N*s/mm)  spring bulge (k = 150 N/mm) } }
})";
  for (const std::string settings : {"", ", substeps = 2, elements = all"}) {
    CAPTURE(settings);
    const Case c = program(hydro, fmt::format("history file = \"ida.csv\"{}", settings));
    REQUIRE(runtime::uses_sundials(c.network(), lang::SolverChoice::automatic));
    const runtime::ProtocolResult whole = check_streamed_is_whole(c, 1);
    CHECK(whole.header.protocol.find("solver=sundials") != std::string::npos);
    const runtime::History& w = std::get<runtime::History>(whole.data);
    double slip = 0.0;  // the slider slips: its elongation leaves its start
    for (std::size_t i = 0; i < w.element_paths.size(); ++i)
      if (w.element_paths[i] == "fluid.cap")
        for (double e : w.element_elongation[i]) slip = std::max(slip, std::abs(e - w.element_elongation[i].front()));
    if (!w.element_paths.empty()) CHECK(slip > 0.01);
    CHECK(w.force.front() != 0.0);  // relaxed away from rest
  }
}

}  // namespace stream_history_test
