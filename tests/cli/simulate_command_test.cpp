// `rheo simulate` with long histories (#28): streamed to the output as they run, the file's
// text what the whole run renders; a fault late in the file reported at its row and column,
// with no output, no temporary file left and earlier outputs intact; standard output and
// --elements stream too.
#include "cli_support.hpp"

#include "lang/frontend.hpp"
#include "runtime/io/output.hpp"
#include "runtime/protocols/run_protocols.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace simulate_command_test {

namespace fs = std::filesystem;
using rheo::test::run_rheo;

namespace {

fs::path dir() { return rheo::test::scratch_directory("simulate-stream"); }

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A history of ROWS rows, its fault (if any) written at row FAULT_ROW as FAULT.
void write_history(const fs::path& path, int rows, int fault_row = -1, const std::string& fault = "") {
  std::ofstream out(path);
  out << "time [s],displacement [mm]\n";
  for (int k = 0; k < rows; ++k)
    out << (k == fault_row ? fault : fmt::format("{},{}", k * 1e-4, 2.0 * std::sin(k * 9.4e-4) + 0.1 * std::sin(k * 0.0145))) << "\n";
}

const std::string kModel =
    "model d {\n  yeoh rubber (D10 = 389.4253 N/mm, D20 = -2.1094 N/mm^3, D30 = 0.0786 N/mm^5)\n  maxwell m1 (k = 61.476 N/mm, tau = 0.004335 s)\n"
    "  friction f1 (k = 1016.6 N/mm, uy = 101.58 um)\n}\n";

}  // namespace

TEST_CASE("simulate streams a history to its output, the text the whole run renders, to files and to standard output, with --elements") {
  write_history(dir() / "long.csv", 80000);  // > 1 MiB: more than one block of the reader
  const fs::path model = dir() / "long.rheo";
  std::ofstream(model) << kModel << "simulate {\n  history file = \"long.csv\", substeps = 2\n  output \"long_out.csv\"\n}\n";
  const auto r = run_rheo(fmt::format("simulate '{}' --elements", model.string()));
  REQUIRE(r.code == 0);
  CHECK(r.err.find("history of model d: 159999 samples written to") != std::string::npos);
  // The whole run, in process: run_protocol and history_csv.
  const rheo::lang::Program program = rheo::lang::compile_source(model.string(), read(model));
  rheo::lang::Protocol protocol = program.simulations.at(0).protocols.at(0);
  std::get<rheo::lang::HistorySettings>(protocol.settings).elements = true;
  const auto network = rheo::runtime::Network::compile(*program.find_model("d"));
  const std::string whole = rheo::runtime::rendered(rheo::runtime::run_protocol(network, protocol, model.string()), rheo::lang::OutputFormat::csv);
  CHECK(read(dir() / "long_out.csv") == whole);
  const auto piped = run_rheo(fmt::format("simulate '{}' --elements -o -", model.string()));
  CHECK(piped.code == 0);
  CHECK(piped.out == whole);
}

// A history IDA runs (`auto` takes it for the inerter) streams too (more than one block of the
// writer), the text the whole run renders.
TEST_CASE("simulate streams a history on IDA, the text the whole run renders") {
  write_history(dir() / "ida.csv", 9000);
  const fs::path model = dir() / "ida.rheo";
  std::ofstream(model) << "model h {\n  spring rubber (k = 800 N/mm)\n  series fluid { slider cap (fy = 60 N)  spring k1 (k = 600 N/mm)\n"
                          "    parallel y { inerter column (b = 40 kg)  dashpot channel (c = 3 N*s/mm)  spring bulge (k = 150 N/mm) } }\n}\n"
                       << "simulate {\n  history file = \"ida.csv\"\n  output \"ida_out.csv\"\n}\n";
  const auto r = run_rheo(fmt::format("simulate '{}'", model.string()));
  REQUIRE(r.code == 0);
  CHECK(r.err.find("history of model h: 9000 samples written to") != std::string::npos);
  const rheo::lang::Program program = rheo::lang::compile_source(model.string(), read(model));
  const auto network = rheo::runtime::Network::compile(*program.find_model("h"));
  const rheo::lang::Protocol& protocol = program.simulations.at(0).protocols.at(0);
  const std::string whole = rheo::runtime::rendered(rheo::runtime::run_protocol(network, protocol, model.string()), rheo::lang::OutputFormat::csv);
  CHECK(whole.find("solver=sundials") != std::string::npos);
  CHECK(read(dir() / "ida_out.csv") == whole);
}

TEST_CASE("a fault late in a streamed history: its row and column, exit 4, no output and no temporary file, earlier outputs intact") {
  write_history(dir() / "late.csv", 120000, 110000, "11,0.5,7");
  const fs::path out = dir() / "late_out";
  fs::create_directories(out);
  std::ofstream(out / "first.csv") << "earlier result\n";
  std::ofstream(out / "second.csv") << "earlier result\n";
  write_history(dir() / "sound.csv", 1000);
  const fs::path model = dir() / "late.rheo";
  std::ofstream(model) << kModel
                       << "simulate {\n  history file = \"sound.csv\"\n  output \"late_out/first.csv\"\n"
                          "  history file = \"late.csv\"\n  output \"late_out/second.csv\"\n}\n";
  const auto r = run_rheo(fmt::format("simulate '{}'", model.string()));
  CHECK(r.code == 4);
  CHECK(r.err.find((dir() / "late.csv").string() + ":110002:8: error: this row has 3 values, the header has 2 columns") != std::string::npos);
  CHECK(read(out / "first.csv") == "earlier result\n");  // the first protocol ran, but nothing is put in place
  CHECK(read(out / "second.csv") == "earlier result\n");
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(out)) ++files;
  CHECK(files == 2);
}

TEST_CASE("simulate --report on a streamed history draws the page of the history held whole, and a longer one in constant memory") {
  write_history(dir() / "drawn.csv", 20000);
  const fs::path model = dir() / "drawn.rheo";
  std::ofstream(model) << kModel << "simulate {\n  history file = \"drawn.csv\"\n}\n";
  // CSV streams (the report from the stream's digest); JSON is held whole (the report from the held history).
  const auto streamed = run_rheo(
      fmt::format("simulate '{}' -o '{}' --report '{}'", model.string(), (dir() / "drawn_out.csv").string(), (dir() / "streamed.html").string()));
  CAPTURE(streamed.err);
  REQUIRE(streamed.code == 0);
  const auto held = run_rheo(fmt::format("simulate '{}' --json -o '{}' --report '{}'", model.string(), (dir() / "drawn_out.json").string(),
                                         (dir() / "held.html").string()));
  REQUIRE(held.code == 0);
  const std::string page = read(dir() / "streamed.html");
  CHECK(page.find("data-figure=\"hysteresis\"") != std::string::npos);
  CHECK(page == read(dir() / "held.html"));
  // Longer than the digest keeps whole (report/history_digest.hpp): a page all the same.
  write_history(dir() / "drawn.csv", 150000);
  const auto longer = run_rheo(
      fmt::format("simulate '{}' -o '{}' --report '{}'", model.string(), (dir() / "drawn_out.csv").string(), (dir() / "longer.html").string()));
  REQUIRE(longer.code == 0);
  CHECK(read(dir() / "longer.html").find("data-figure=\"hysteresis\"") != std::string::npos);
  CHECK(read(dir() / "drawn_out.csv").find("\n14.9999") != std::string::npos);  // the output is whole
}

}  // namespace simulate_command_test
