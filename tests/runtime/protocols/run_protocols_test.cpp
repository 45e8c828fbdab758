// Protocol runs from `simulate` blocks: a history read from CSV against the generated drive of
// the same programme (two paths to the same displacement), JSON output, relaxation steps.
#include "runtime/protocols/run_protocols.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/io/harmonic_data.hpp"
#include "runtime/io/history_csv.hpp"
#include "runtime/io/output.hpp"
#include "support.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

namespace run_protocols_test {

using namespace rheo;

namespace {
// The first protocol's result, and its text in the format the protocol names.
struct Run {
  runtime::ProtocolResult result;
  std::string content;
  const std::string& notes() const { return result.notes; }
};
Run run_first(const std::string& source, const std::string& file) {
  const lang::Program program = lang::compile_source(file, source);
  const auto network = runtime::Network::compile(*program.find_model(program.simulations.at(0).model));
  const lang::Protocol& protocol = program.simulations.at(0).protocols.at(0);
  runtime::ProtocolResult result = runtime::run_protocol(network, protocol, file);
  std::string content = runtime::rendered(result, lang::common(protocol.settings).format);
  return {std::move(result), std::move(content)};
}
const char* kSpecimenD = R"(
model d {
  yeoh     rubber (D10 = 389.4253 N/mm, D20 = -2.1094 N/mm^3, D30 = 0.0786 N/mm^5)
  maxwell  m1 (k = 61.476 N/mm, tau = 0.004335 s)
  friction f1 (k = 1016.6 N/mm, uy = 101.58 um)
  friction f2 (k = 301.04 N/mm, uy = 42.256 um)
}
)";
}  // namespace

TEST_CASE("a history read from CSV reproduces the static protocol on the same programme") {
  const std::string data_file = std::string(RHEO_DATA_DIR) + "/specimen_D_static.csv";
  const auto from_csv = run_first(std::string(kSpecimenD) + "simulate { history file = \"" + data_file + "\" }", "d.rheo");
  const auto generated = run_first(
      std::string(kSpecimenD) + "simulate { static velocity = 0.05 mm/s, amplitude = [6.25, 3.0, 1.2, 0.6, 0.3, 0.12] mm }", "d.rheo");
  const auto a = runtime::parse_table("csv", from_csv.content), b = runtime::parse_table("gen", generated.content);
  REQUIRE(a.rows.size() == b.rows.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < a.rows.size(); ++i) worst = std::max(worst, std::abs(a.columns[2][i] - b.columns[2][i]));
  CHECK(worst < 1e-6);  // the CSV rounds displacements to 1e-6 mm
}

TEST_CASE("json output carries units and every point") {
  const auto run = run_first("model m { spring s (k = 10) }\nsimulate { harmonic frequency = [1, 2] Hz, amplitude = 1 mm, format = json }", "m.rheo");
  const auto j = nlohmann::json::parse(run.content);
  CHECK(j["units"]["stiffness"] == "N/mm");
  REQUIRE(j["points"].size() == 2);
  CHECK(j["points"][1]["stiffness"].get<double>() == doctest::Approx(10.0));
}

TEST_CASE("harmonic with a preload: a preload column, and the result read back as measured data keeps its preload") {
  const auto run = run_first(std::string(kSpecimenD) + "simulate { harmonic frequency = [1, 11] Hz, amplitude = [0.2, 1] mm, preload = 2 mm }",
                             "d.rheo");
  const auto table = runtime::parse_table("result.csv", run.content);
  REQUIRE(table.column("preload") >= 0);
  const auto data = runtime::harmonic_data_from_table(table);
  REQUIRE(data.size() == 4);
  for (double p : data.preload) CHECK(p == 2.0);
  const auto centred = runtime::harmonic_data_from_table(runtime::parse_table(
      "c.csv", run_first(std::string(kSpecimenD) + "simulate { harmonic frequency = [1, 11] Hz, amplitude = [0.2, 1] mm }", "d.rheo").content));
  CHECK(centred.preload == std::vector<double>(4, 0.0));
  // 12 D20 p^2 + 30 D30 p^4 = -63 N/mm: the preloaded rubber is softer at small amplitude.
  CHECK(data.stiffness[0] < centred.stiffness[0] - 30.0);
}

TEST_CASE("step protocol with element outputs: the Maxwell arm relaxes, the spring holds") {
  const auto run = run_first(
      "model z { spring e (k = 10) maxwell m (k = 5, tau = 0.1 s) }\nsimulate { step amplitude = 2 mm, duration = 1 s, dt = 1 ms, elements = all }",
      "z.rheo");
  const auto t = runtime::parse_table("z", run.content);
  CHECK(t.column("e.force") >= 0);
  const auto& spring = t.columns[static_cast<std::size_t>(t.column("e.force"))];
  const auto& arm = t.columns[static_cast<std::size_t>(t.column("m.force"))];
  CHECK(spring.back() == doctest::Approx(20.0));
  CHECK(arm.back() == doctest::Approx(arm[1] * std::exp(-(1.0 - 1e-3) / 0.1)).epsilon(1e-9).scale(0.0));
}

TEST_CASE("solver = sundials names itself in the header, with steady_state = closed_form it is a usage error") {
  const std::string model = "model m { spring k (k = 100 N/mm)\n maxwell x (k = 50 N/mm, tau = 10 ms) }\n";
  const auto run = run_first(model + "simulate { harmonic frequency = 5 Hz, amplitude = 0.5 mm, solver = sundials }", "s.rheo");
  CHECK(run.content.find("solver=sundials (IDA") != std::string::npos);
  CHECK_THROWS_WITH_AS(
      run_first(model + "simulate { harmonic frequency = 5 Hz, amplitude = 0.5 mm, solver = sundials, steady_state = closed_form }", "s.rheo"),
      doctest::Contains("s.rheo:3:12: steady_state = closed_form and the SUNDIALS solver exclude each other"), runtime::UsageError);
}

TEST_CASE("a yeoh driven past where it softens: a warning in the root block (once per protocol), an error in series") {
  const std::string soft = "model y { yeoh r (D10 = 1, D20 = -1, D30 = 0) spring k (k = 1) }\n";  // e* = 1/sqrt(6) mm
  const auto past = run_first(soft + "simulate { harmonic frequency = 1 Hz, amplitude = [0.1, 2] mm }", "y.rheo");
  CHECK(past.notes() ==
        "warning: yeoh 'r' softens to zero tangent stiffness at |e| = 0.408248 mm (eq. 3.3) and the drive reaches "
        "2 mm: its force falls beyond that; bound D20 so that D20^2 < (5/3) D10 D30 (a Yeoh law that stiffens again)\n");
  CHECK(run_first(soft + "simulate { harmonic frequency = 1 Hz, amplitude = [0.1, 0.4] mm }", "y.rheo").notes().empty());
  const auto history = run_first(soft + "simulate { static velocity = 1 mm/s, amplitude = 0.5 mm }", "y.rheo");
  CHECK(history.notes().find("the drive reaches 0.5 mm") != std::string::npos);
  const std::string chain = "model y { series { yeoh r (D10 = 1, D20 = -1, D30 = 0) spring k (k = 1) } }\n";
  CHECK_THROWS_WITH_AS(run_first(chain + "simulate { static velocity = 1 mm/s, amplitude = 2 mm }", "y.rheo"),
                       doctest::Contains("yeoh 'r' is asked to carry"), runtime::NumericalError);
}

TEST_CASE("work limits: a protocol asking for more samples or steps than lang/limits.hpp allows fails before allocating") {
  const std::string model = "model m { spring k (k = 100 N/mm) }\n";
  auto fails = [&](const std::string& protocol, const char* message) {
    CAPTURE(protocol);
    CHECK_THROWS_WITH_AS(run_first(model + "simulate {\n  " + protocol + " }", "w.rheo"), doctest::Contains(message), runtime::ModelError);
  };
  // 2 amplitudes x 100000 cycles x 400 steps = 8e7 samples.
  fails("static velocity = 1 mm/s, amplitude = [1, 2] mm, cycles = 100000",
        "w.rheo:3:3: error: the static protocol asks for 8e+07 samples, more than the limit of 10000000; raise dt or velocity");
  // dt cuts each of the 400 steps of a 1 mm cycle (4 mm at 1 mm/s: 10 ms per step) into 10000 parts.
  fails("static velocity = 1 mm/s, amplitude = 1 mm, cycles = 3, dt = 1 us", "asks for 1.2e+07 samples");
  fails("quasistatic frequency = 1 Hz, amplitude = 1 mm, cycles = 100, steps_per_cycle = 1000000", "asks for 1e+08 samples");
  fails("step amplitude = 1 mm, duration = 1000 s, dt = 1 us", "asks for 1e+09 samples (duration / dt)");
  fails("harmonic frequency = 1 Hz .. 1000 Hz step 1 Hz, amplitude = 0.001 mm .. 1.001 mm step 0.001 mm",
        "asks for 1.001e+06 points (amplitudes x frequencies), more than the limit of 1000000");
  fails("harmonic frequency = 1 Hz, amplitude = 1 mm, steps_per_cycle = 1000000",
        "asks for 4e+08 time steps per point (steps_per_cycle x cycles_max), more than the limit of 100000000; lower");
  // At the limits they run: 10^7 samples are not built here, but the largest cheap case is.
  CHECK(run_first(model + "simulate { step amplitude = 1 mm, duration = 1 s, dt = 1 ms }", "w.rheo").result.size() == 1001);
}

}  // namespace run_protocols_test
