// The co-simulation instance against closed forms of held and ramped inputs, against rheo's own
// history runs on the same piecewise-linear path, and its errors: each leaves the instance as it
// was.
#include "runtime/fmu/cosimulation.hpp"

#include "runtime/protocols/run_history.hpp"
#include "runtime/stepping/drive_stepper.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace cosimulation_test {

using namespace rheo;
using runtime::fmu::CoSimulation;

namespace {

CoSimulation started(const std::string& source, const std::string& model, double u0 = 0.0) {
  CoSimulation c("test.rheo", source, model);
  c.setup_experiment(0.0, std::nullopt);
  c.enter_initialization();
  c.set_real(runtime::fmu::kInputU, u0);
  c.exit_initialization();
  return c;
}

unsigned reference_of(const CoSimulation& c, const std::string& name) {
  for (const auto& v : c.variables())
    if (v.name == name) return v.reference;
  FAIL("no variable " << name);
  return 0;
}

double force(const CoSimulation& c) { return c.get_real(runtime::fmu::kOutputF); }

}  // namespace

TEST_CASE("fmu: a held step input relaxes a root Maxwell arm as k U exp(-t/tau), exactly (eq. B.53)") {
  const double k = 61.476, tau = 4.335e-3, U = 0.5, h = 1e-3;
  CoSimulation c = started("model m { maxwell m1 (k = 61.476 N/mm, tau = 4.335 ms) }", "m");
  c.set_real(runtime::fmu::kInputU, U);
  for (int n = 1; n <= 40; ++n) {
    c.do_step((n - 1) * h, h);
    // The jump at t = 0 is instantaneous for a root block: the arm's spring takes k U at once.
    CHECK(test::relative_error(force(c), k * U * std::exp(-n * h / tau)) < 1e-12);
  }
}

TEST_CASE("fmu: a held input is a jump then a hold: a root dashpot carries nothing at the step's end, a spring k u") {
  CoSimulation c = started("model kv { spring s (k = 20 N/mm) dashpot d (c = 3 N*s/mm) }", "kv");
  const double h = 2e-3;
  double u = 0.0;
  for (int n = 0; n < 10; ++n) {
    u += 0.1 * (n % 3 == 0 ? -1.0 : 1.0);
    c.set_real(runtime::fmu::kInputU, u);
    c.do_step(n * h, h);
    CHECK(force(c) == doctest::Approx(20.0 * u).epsilon(1e-14));
  }
}

TEST_CASE("fmu: with input derivatives the input is a ramp: spring + dashpot give k u + c du/dt at every step's end") {
  CoSimulation c = started("model kv { spring s (k = 20 N/mm) dashpot d (c = 3 N*s/mm) }", "kv");
  const double h = 1e-3, v = 40.0;  // mm/s
  for (int n = 0; n < 25; ++n) {
    c.set_real(runtime::fmu::kInputU, v * n * h);
    c.set_input_derivative(runtime::fmu::kInputU, 1, v);
    c.do_step(n * h, h);
    CHECK(force(c) == doctest::Approx(20.0 * v * (n + 1) * h + 3.0 * v).epsilon(1e-12));
  }
  // The derivative holds for one step only: the next step, without one, holds u (a ramp would
  // give 20 u + 3 v + 20 v h).
  c.set_real(runtime::fmu::kInputU, v * 25 * h);
  c.do_step(25 * h, h);
  CHECK(force(c) == doctest::Approx(20.0 * v * 25 * h).epsilon(1e-12));
}

TEST_CASE("fmu: the input v makes the step a ramp as long as it is set, and a derivative overrides it for one step") {
  CoSimulation c = started("model kv { spring s (k = 20 N/mm) dashpot d (c = 3 N*s/mm) }", "kv");
  const double h = 1e-3, v = 40.0;  // mm/s
  c.set_real(runtime::fmu::kInputV, v);
  for (int n = 0; n < 5; ++n) {
    c.set_real(runtime::fmu::kInputU, v * n * h);
    c.do_step(n * h, h);
    CHECK(force(c) == doctest::Approx(20.0 * v * (n + 1) * h + 3.0 * v).epsilon(1e-12));
  }
  c.set_real(runtime::fmu::kInputU, v * 5 * h);
  c.set_input_derivative(runtime::fmu::kInputU, 1, -v);
  c.do_step(5 * h, h);
  CHECK(force(c) == doctest::Approx(20.0 * v * 4 * h - 3.0 * v).epsilon(1e-12));
  c.set_real(runtime::fmu::kInputU, v * 4 * h);  // where the ramp ended: v holds again
  c.do_step(6 * h, h);
  CHECK(force(c) == doctest::Approx(20.0 * v * 5 * h + 3.0 * v).epsilon(1e-12));
  CHECK(c.get_real(runtime::fmu::kInputV) == v);
  CHECK_THROWS_AS(c.set_input_derivative(runtime::fmu::kInputV, 1, 1.0), UsageError);
  CHECK_THROWS_AS(c.set_real(runtime::fmu::kInputV, std::numeric_limits<double>::infinity()), DataError);
}

TEST_CASE("fmu: a jump into a subtree is a ramp over h/2^10 then a hold, as rheo's history run of that path") {
  // Springs k2 and k in series with the dashpot c: a Maxwell arm of K = k k2/(k + k2), tau' = c/K.
  const double k = 100, k2 = 300, c = 1.5, K = k * k2 / (k + k2), tau = c / K, U = 0.2, h = 1e-3;  // tau' = 20 ms
  const std::string source = "model sls { series arm { spring k2 (k = 300 N/mm) maxwell m (k = 100 N/mm, c = 1.5 N*s/mm) } }";
  CoSimulation sim = started(source, "sls");
  sim.set_real(runtime::fmu::kInputU, U);
  runtime::Drive drive{{0.0, h * runtime::fmu::kJumpFraction}, {0.0, U}};
  for (int n = 1; n <= 30; ++n) {
    drive.time.push_back(n * h);
    drive.displacement.push_back(U);
  }
  // The FMU takes one kernel step a host step (its host sets h), so the history it is compared
  // with takes one step a sample too, without the error control of rheo's histories
  // (stepping/drive_stepper.hpp).
  const runtime::Network network = runtime::Network::compile(sim.model());
  runtime::DriveStepper stepper(network, false, 0.0);
  std::vector<double> reference{stepper.start(drive.time[0], drive.displacement[0])};
  for (std::size_t i = 1; i < drive.time.size(); ++i) reference.push_back(stepper.step(drive.time[i], drive.displacement[i]));
  for (int n = 1; n <= 30; ++n) {
    sim.do_step((n - 1) * h, h);
    CHECK(test::relative_error(force(sim), reference[static_cast<std::size_t>(n + 1)]) < 1e-12);
    // The closed form of an instantaneous jump, within what the ramp over delta = h/2^10 relaxes
    // the arm before the hold, delta/(2 tau') = 2.4e-5, and the fixed-step kernels' first-order
    // error of a chain with an internal node (docs/numerics.md), about 3.5e-6 per step at
    // h/tau' = 0.05. Missing the jump or the hold would be off by tens of percent.
    CHECK(test::relative_error(force(sim), K * U * std::exp(-n * h / tau)) < 2.5e-5 + 4e-6 * n);
  }
}

TEST_CASE("fmu: on a continuous piecewise-linear input given as ramps the FMU is rheo's own history run (hydrobushing)") {
  const std::string source = test::read_file(std::string(RHEO_EXAMPLES_DIR) + "/hydrobushing.rheo");
  CoSimulation c = started(source, "hydrobushing");
  const double h = 5e-4;
  runtime::Drive drive;
  for (int n = 0; n <= 400; ++n) {
    drive.time.push_back(n * h);
    drive.displacement.push_back(0.8 * std::sin(2 * std::numbers::pi * 15.0 * n * h) + 0.3 * std::sin(2 * std::numbers::pi * 4.0 * n * h));
  }
  const auto reference = runtime::run_history(runtime::Network::compile(c.model()), drive, false, runtime::SolverChoice::fixed);
  double peak = 0.0, worst = 0.0;
  for (std::size_t n = 0; n + 1 < drive.time.size(); ++n) {
    c.set_real(runtime::fmu::kInputU, drive.displacement[n]);
    c.set_input_derivative(runtime::fmu::kInputU, 1, (drive.displacement[n + 1] - drive.displacement[n]) / h);
    c.do_step(drive.time[n], h);
    peak = std::max(peak, std::abs(reference.force[n + 1]));
    worst = std::max(worst, std::abs(force(c) - reference.force[n + 1]));
  }
  CHECK(peak > 100.0);
  CHECK(worst <= 1e-12 * peak);
}

TEST_CASE("fmu: initialisation starts relaxed at the input u, with the parameters as set") {
  CoSimulation c("test.rheo", "model m { spring s (k = 20 N/mm) maxwell m1 (k = 50 N/mm, tau = 1 ms) }", "m");
  c.enter_initialization();
  c.set_real(reference_of(c, "s.k"), 30.0);
  c.set_real(reference_of(c, "m1.tau"), 2e-3);
  c.set_real(runtime::fmu::kInputU, 0.4);
  CHECK(c.get_real(reference_of(c, "m1.c")) == doctest::Approx(50.0 * 2e-3).epsilon(1e-15).scale(0.0));  // c = k tau, recomputed
  CHECK(force(c) == doctest::Approx(30.0 * 0.4).epsilon(1e-15));                                         // the Maxwell arm relaxed
  c.exit_initialization();
  CHECK(force(c) == doctest::Approx(12.0).epsilon(1e-15));
  c.set_real(runtime::fmu::kInputU, 0.5);
  c.do_step(0.0, 1e-3);
  CHECK(force(c) == doctest::Approx(30.0 * 0.5 + 50.0 * 0.1 * std::exp(-0.5)).epsilon(1e-12));
}

TEST_CASE("fmu: a restored FMU state repeats the steps after it bit for bit, also through its serialized bytes") {
  const std::string source = test::read_file(std::string(RHEO_EXAMPLES_DIR) + "/hydrobushing.rheo");
  CoSimulation c = started(source, "hydrobushing");
  auto drive = [](int n) { return 0.5 * std::sin(0.07 * n); };
  const double h = 1e-3;
  for (int n = 0; n < 50; ++n) {
    c.set_real(runtime::fmu::kInputU, drive(n));
    c.do_step(n * h, h);
  }
  const runtime::fmu::Snapshot saved = c.snapshot();
  const std::string bytes = c.serialize(saved);
  std::vector<double> first;
  for (int n = 50; n < 100; ++n) {
    c.set_real(runtime::fmu::kInputU, drive(n));
    c.do_step(n * h, h);
    first.push_back(force(c));
  }
  for (const auto& state : {saved, c.deserialize(bytes)}) {
    c.restore(state);
    for (int n = 50; n < 100; ++n) {
      c.set_real(runtime::fmu::kInputU, drive(n));
      c.do_step(n * h, h);
      CHECK(force(c) == first[static_cast<std::size_t>(n - 50)]);
    }
  }
}

TEST_CASE("fmu: bad values and calls out of sequence are typed errors that change nothing") {
  CoSimulation c = started("model m { spring s (k = 20 N/mm) maxwell m1 (k = 50 N/mm, tau = 1 ms) }", "m");
  c.set_real(runtime::fmu::kInputU, 0.3);
  c.do_step(0.0, 1e-3);
  const runtime::fmu::Snapshot before = c.snapshot();
  auto unchanged = [&] {
    CHECK(c.time() == before.time);
    CHECK(c.get_real(runtime::fmu::kInputU) == before.input);
    CHECK(force(c) == before.state.force);
  };
  CHECK_THROWS_AS(c.set_real(runtime::fmu::kInputU, std::numeric_limits<double>::quiet_NaN()), DataError);
  CHECK_THROWS_AS(c.set_real(runtime::fmu::kInputU, 1e21), DataError);
  CHECK_THROWS_AS(c.set_real(runtime::fmu::kOutputF, 1.0), UsageError);
  CHECK_THROWS_AS(c.set_real(reference_of(c, "s.k"), 25.0), UsageError);  // fixed after initialisation
  CHECK_THROWS_AS(c.set_real(99, 1.0), UsageError);
  CHECK_THROWS_AS(c.set_input_derivative(runtime::fmu::kInputU, 2, 1.0), UsageError);
  CHECK_THROWS_AS(c.set_input_derivative(runtime::fmu::kInputU, 1, std::numeric_limits<double>::infinity()), DataError);
  CHECK_THROWS_WITH_AS(c.do_step(1e-3, 0.0), doctest::Contains("step size 0 s"), UsageError);
  CHECK_THROWS_AS(c.do_step(1e-3, -1e-3), UsageError);
  CHECK_THROWS_AS(c.do_step(1e-3, std::numeric_limits<double>::quiet_NaN()), UsageError);
  CHECK_THROWS_WITH_AS(c.do_step(5e-3, 1e-3), doctest::Contains("the FMU is at t = 0.001 s"), UsageError);
  CHECK_THROWS_AS(c.enter_initialization(), UsageError);
  unchanged();
  CHECK_THROWS_AS(c.deserialize("not a state"), DataError);
  CHECK_THROWS_AS(c.deserialize(c.serialize(before).substr(0, 40)), DataError);
  unchanged();
  c.do_step(1e-3, 1e-3);  // and it goes on
  CHECK(c.time() == doctest::Approx(2e-3).scale(0.0));
}

TEST_CASE("fmu: a step past the stop time, and parameters outside their bounds, are refused") {
  CoSimulation c("test.rheo", "model m { spring s (k = 20 N/mm in [1, 100]) }", "m");
  c.setup_experiment(0.0, 1e-2);
  c.enter_initialization();
  CHECK_THROWS_WITH_AS(c.set_real(reference_of(c, "s.k"), 200.0), doctest::Contains("outside its range [1, 100]"), DataError);
  CHECK(c.get_real(reference_of(c, "s.k")) == 20.0);
  c.exit_initialization();
  for (int n = 0; n < 10; ++n) c.do_step(n * 1e-3, 1e-3);
  CHECK_THROWS_WITH_AS(c.do_step(1e-2, 1e-3), doctest::Contains("past the stop time"), UsageError);
}

TEST_CASE("fmu: FMI 3.0 enters initialisation with the experiment's times in one call, and its messages name the fmi3 functions") {
  CoSimulation c("test.rheo", "model m { spring s (k = 20 N/mm) }", "m", runtime::fmu::FmiVersion::fmi3);
  CHECK_THROWS_WITH_AS(c.enter_initialization(0.0, -1.0), doctest::Contains("stop time -1 s lies before the start time 0 s"), DataError);
  CHECK(c.phase() == runtime::fmu::Phase::instantiated);  // the failed call changed nothing
  c.enter_initialization(0.5, 0.5 + 4e-3);
  CHECK(c.phase() == runtime::fmu::Phase::initialization);
  CHECK_THROWS_WITH_AS(c.enter_initialization(0.0, std::nullopt),
                       doctest::Contains("fmi3EnterInitializationMode is called once after instantiation"), UsageError);
  c.exit_initialization();
  CHECK(c.time() == 0.5);
  CHECK_THROWS_WITH_AS(c.do_step(0.0, 1e-3), doctest::Contains("restore an FMU state (fmi3SetFMUState)"), UsageError);
  CHECK_THROWS_WITH_AS(c.set_real(reference_of(c, "s.k"), 25.0), doctest::Contains("set it before fmi3ExitInitializationMode"), UsageError);
  for (int n = 0; n < 4; ++n) c.do_step(0.5 + n * 1e-3, 1e-3);
  CHECK_THROWS_WITH_AS(c.do_step(0.504, 1e-3), doctest::Contains("s (fmi3EnterInitializationMode)"), UsageError);
  // FMI 2.0 names its own.
  CoSimulation two("test.rheo", "model m { spring s (k = 20 N/mm) }", "m");
  CHECK_THROWS_WITH_AS(two.do_step(0.0, 1e-3),
                       doctest::Contains("fmi2DoStep is called after initialisation, not instantiated (before fmi2EnterInitializationMode)"),
                       UsageError);
}

TEST_CASE("fmu: the independent variable time reads the last communication point and cannot be set") {
  CoSimulation c = started("model m { spring s (k = 20 N/mm) }", "m");
  const unsigned time = reference_of(c, "time");
  CHECK(time == c.variables().size() - 1);
  CHECK(c.get_real(time) == 0.0);
  for (int n = 0; n < 3; ++n) c.do_step(n * 0.25, 0.25);  // exact in binary
  CHECK(c.get_real(time) == 0.75);
  CHECK_THROWS_WITH_AS(c.set_real(time, 1.0), doctest::Contains("time is the independent variable"), UsageError);
  CHECK(c.get_real(time) == 0.75);
}

}  // namespace cosimulation_test
