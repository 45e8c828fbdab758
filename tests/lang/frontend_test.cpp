#include "lang/frontend.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <string_view>

namespace frontend_test {

using namespace rheo::lang;

namespace {
const char* kBushing = R"(# Thesis specimen D
model bushing_d {
  parallel {
    yeoh     rubber (D10 = 389.43 N/mm, D20 = -2.1094 N/mm^3, D30 = 0.0786 N/mm^5)
    maxwell  m1     (k = 61.476 N/mm, tau = 4.335 ms)
    friction f1     (k = 1016.6 N/mm, uy = 101.58 um)
    friction f2     (k = 301.04 N/mm, uy = 42.256 um)
  }
}
simulate {
  harmonic frequency = 1 Hz .. 51 Hz step 2 Hz, amplitude = [0.2, 0.5, 1.0, 3.0] mm
  output "bushing_d_harmonic.csv"
}
)";

const Parameter& find(const CheckedModel& m, const std::string& path) {
  for (const auto& p : m.parameters)
    if (p.path == path) return p;
  FAIL("no parameter " << path);
  throw;
}
}  // namespace

TEST_CASE("compile_source: the thesis example becomes a checked Program in internal units") {
  Program p = compile_source("d.rheo", kBushing);
  REQUIRE(p.models.size() == 1);
  const CheckedModel& m = p.models[0];
  CHECK(m.name == "bushing_d");
  REQUIRE(m.root.children.size() == 1);
  const Element& block = m.root.children[0];
  CHECK(block.kind == ElementKind::parallel);
  REQUIRE(block.children.size() == 4);
  const Element& m1 = block.children[1];
  CHECK(m1.kind == ElementKind::maxwell);
  CHECK(m1.path == "m1");
  REQUIRE(m1.parameters.size() == 2);
  const Parameter& c = m.parameters[static_cast<std::size_t>(m1.parameters[1])];
  CHECK(c.path == "m1.c");
  CHECK(c.dimension == dim::damping);
  CHECK(c.value == doctest::Approx(61.476 * 4.335e-3).scale(0.0));
  CHECK_FALSE(c.expression.is_constant());
  const Element& f1 = block.children[2];
  CHECK(m.parameters[static_cast<std::size_t>(f1.parameters[1])].value == doctest::Approx(1016.6 * 0.10158));
  CHECK(find(m, "rubber.D20").value == doctest::Approx(-2.1094));

  REQUIRE(p.simulations.size() == 1);
  const auto& sim = p.simulations[0];
  CHECK(sim.model == "bushing_d");
  REQUIRE(sim.protocols.size() == 1);
  const Protocol& h = sim.protocols[0];
  CHECK(h.kind == ProtocolKind::harmonic);
  CHECK(h.output == "bushing_d_harmonic.csv");
  const auto& settings = std::get<HarmonicSettings>(h.settings);
  CHECK(settings.frequencies.size() == 26);
  CHECK(settings.frequencies.back() == 51.0);
  CHECK(settings.amplitudes == std::vector<double>{0.2, 0.5, 1.0, 3.0});
}

TEST_CASE("compile_source: every semantic error is reported, formatted with line and caret") {
  try {
    compile_source("x.rheo", "model m {\n  spring k1 (k = 5 mm)\n  dashpot (c = -1)\n}\n");
    FAIL("expected a CompileError");
  } catch (const CompileError& e) {
    REQUIRE(e.diagnostics().size() == 2);
    const std::string text = e.what();
    CHECK(text.find("x.rheo:2:18: error: k of spring 'k1' expects a stiffness (N/mm), got a length (mm)\n"
                    "    spring k1 (k = 5 mm)\n"
                    "                   ^\n") != std::string::npos);
    CHECK(text.find("x.rheo:3:16: error: damping c of dashpot 'dashpot1' must be positive, got -1 N*s/mm") != std::string::npos);
  }
}

TEST_CASE("compile_source: imported stdlib models are part of the Program, not counted for simulate") {
  Program p = compile_source("i.rheo", "import zener\nmodel m { zener z (k1 = 2 * 10 N/mm) }\nsimulate { step amplitude = 1 mm, duration = 1 s }");
  REQUIRE(p.models.size() == 2);
  CHECK(p.models[0].name == "zener");
  CHECK(p.simulations[0].model == "m");
  const CheckedModel* m = p.find_model("m");
  REQUIRE(m);
  CHECK(find(*m, "z.k1").value == 20.0);
  CHECK(find(*m, "z.arm1.k").value == 20.0);  // the override propagates through the reference
  CHECK(find(*m, "z.arm1.c").value == doctest::Approx(20.0 * 0.01).scale(0.0));
  CHECK(p.find_model("nope") == nullptr);
}

TEST_CASE("load_program: an unreadable file or a directory is an UnreadableSource naming it") {
  CHECK_THROWS_WITH_AS(load_program("/nonexistent/file.rheo"),
                       "/nonexistent/file.rheo: error: cannot read it (No such file or directory); check the path", UnreadableSource);
  CHECK_THROWS_WITH_AS(load_program(RHEO_CORPUS_DIR), doctest::Contains("cannot read it (it is a directory)"), UnreadableSource);
}

TEST_CASE("parse_setting: command-line settings use the value grammar and the protocol schema") {
  Setting s = parse_setting(ProtocolKind::harmonic, "frequency = 1 Hz .. 51 Hz step 2 Hz");
  CHECK(s.key == "frequency");
  CHECK(s.values.size() == 26);
  CHECK(s.dimension == dim::frequency);
  Setting a = parse_setting(ProtocolKind::static_triangle, "amplitude = [0.2 mm, 500 um]");
  CHECK(a.values == std::vector<double>{0.2, 0.5});
  CHECK(parse_setting(ProtocolKind::harmonic, "definition = thesis").text == "thesis");
  CHECK_THROWS_WITH_AS(parse_setting(ProtocolKind::harmonic, "frequency = 2 mm"),
                       doctest::Contains("<command line>:1:13: error: frequency expects a frequency (1/s), got a length (mm)"), CompileError);
  CHECK_THROWS_WITH_AS(parse_setting(ProtocolKind::harmonic, "frequency = 2 Hz )"), doctest::Contains("unexpected text"), CompileError);
}

TEST_CASE("parse_data_option: --data takes a data line's settings, with its grammar and checks") {
  const FitData plain = parse_data_option("dir/sweep 1.csv");  // no comma: the file as it stands
  CHECK(plain.file == "dir/sweep 1.csv");
  CHECK(plain.weight == 1.0);
  CHECK(plain.columns.empty());
  const FitData d = parse_data_option(
      R"(sweep.txt, step = "Amplitude sweep", area = 314 mm^2, height = 1 mm, columns = "frequency = f", weight = 0.5)");
  CHECK(d.file == "sweep.txt");
  CHECK(d.step == "Amplitude sweep");
  CHECK(d.area == 314.0);
  CHECK(d.height == 1.0);
  CHECK(d.weight == 0.5);
  REQUIRE(d.columns.size() == 1);
  CHECK(d.columns[0].role == "frequency");
  CHECK(d.columns[0].name == "f");
  CHECK(parse_data_option(R"("a, b.csv", amplitude = 0.1 %)").file == "a, b.csv");
  CHECK(parse_data_option(R"("a, b.csv", amplitude = 0.1 %)").amplitude_is_strain);
  CHECK(parse_data_option("a.csv, duplicates = error").duplicates == DuplicatePoints::error);
  CHECK_THROWS_WITH_AS(parse_data_option("a.csv, colums = \"f = x\""),
                       doctest::Contains("<command line>:1:8: error: unknown setting 'colums' for a data line"), CompileError);
  CHECK_THROWS_WITH_AS(parse_data_option("a.csv, area = 3 mm"), doctest::Contains("<command line>:1:15: error: area expects an area"), CompileError);
  CHECK_THROWS_WITH_AS(parse_data_option("a.csv, weight = 1, weight = 2"), doctest::Contains("duplicate setting 'weight'"), CompileError);
  CHECK_THROWS_WITH_AS(parse_data_option("a.csv, columns = \"speed = v\""), doctest::Contains("'speed' is not a role rheo reads"), CompileError);
  CHECK_THROWS_WITH_AS(parse_data_option(", weight = 1"), doctest::Contains("1:1: error: expected the data file name before the first ','"),
                       CompileError);
}

namespace {
// Seconds compile_source takes on TEXT; the errors it reports go to ERRORS.
double seconds_to_compile(const std::string& text, std::vector<Diagnostic>& errors, std::size_t& formatted) {
  const auto start = std::chrono::steady_clock::now();
  try {
    compile_source("big.rheo", text);
  } catch (const CompileError& e) {
    errors = e.diagnostics();
    formatted = std::string_view(e.what()).size();
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

TEST_CASE("compile_source: 10 MB files check in time and memory proportional to their size") {
  constexpr std::size_t ten_mb = 10'000'000;
  std::vector<Diagnostic> errors;
  std::size_t formatted = 0;
  // A 10 MB comment on one line.
  CHECK(seconds_to_compile("model m { spring s (k = 1 N/mm) }\n# " + std::string(ten_mb, 'x') + "\n", errors, formatted) < 20.0);
  CHECK(errors.empty());
  // 10 MB of parameters, each referring to the one declared after it.
  std::string chain = "model m {\n";
  int n = 0;
  for (; chain.size() < ten_mb; ++n) chain += fmt::format("  param p{} = p{} + 1 N/mm\n", n, n + 1);
  CHECK(seconds_to_compile(chain + fmt::format("  param p{} = 1 N/mm\n  spring s (k = p0)\n}}\n", n), errors, formatted) < 20.0);
  CHECK(errors.empty());
  // 10 MB on one line, one error per element: each quotes the line around its column only.
  std::string line = "model m {";
  for (int i = 0; line.size() < ten_mb; ++i) line += fmt::format(" spring s{} (k = q{})", i, i);
  CHECK(seconds_to_compile(line + " }\n", errors, formatted) < 20.0);
  CHECK(errors.size() > 300000);
  CHECK(formatted < 600 * errors.size());
}

}  // namespace frontend_test
