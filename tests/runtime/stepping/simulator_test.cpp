// Time-domain kernels against hand-derived solutions: Maxwell relaxation, the friction
// parallelogram (Fig. B.29), and a slider in series with a Maxwell element (the chapter 9
// building block), all exact under a piecewise-linear drive.
#include "runtime/stepping/simulator.hpp"

#include "runtime/protocols/run_history.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

namespace simulator_test {

using namespace rheo;

TEST_CASE("a Maxwell element relaxes as exp(-t/tau) after a step (eq. B.53)") {
  const auto net = test::network_from("model m { maxwell m (k = 61.476, tau = 4.335 ms) }", "m");
  const double dt = 1e-4, tau = 4.335e-3, u0 = 0.5;
  const auto h = runtime::run_history(net, runtime::step_relaxation(u0, dt, 0.05, dt), false);
  const double f1 = h.force[1];
  // Force after a ramp over one step: k tau (1 - exp(-dt/tau)) / dt * u0  (exact for a linear ramp).
  CHECK(test::relative_error(f1, 61.476 * tau * (1 - std::exp(-dt / tau)) / dt * u0) < 1e-12);
  for (std::size_t k = 2; k < h.time.size(); k += 37) CHECK(test::relative_error(h.force[k], f1 * std::exp(-(h.time[k] - dt) / tau)) < 1e-10);
}

TEST_CASE("relaxation times far below the step stay stable and relax within the step") {
  const auto net = test::network_from("model m { spring e (k = 10) maxwell m (k = 1e6, tau = 1e-9 s) }", "m");
  const auto h = runtime::run_history(net, runtime::step_relaxation(1.0, 1e-3, 0.01, 1e-3), false);
  for (std::size_t k = 1; k < h.time.size(); ++k) {
    CHECK(std::isfinite(h.force[k]));
    CHECK(h.force[k] >= 10.0 * h.displacement[k] - 1e-9);
  }
  // The Maxwell arm acts as a dashpot c = k tau = 1e-3 N*s/mm during the ramp: 1e-3 * 1 mm / 1 ms = 1 N.
  CHECK(std::abs(h.force[1] - (10.0 + 1.0)) < 1e-6);
  CHECK(std::abs(h.force[2] - 10.0) < 1e-9);
}

TEST_CASE("spring + friction element: the loop is the analytic parallelogram (Fig. B.29)") {
  const double ke = 50, k = 400, fy = 12, amplitude = 0.2;  // slip displacement 0.03 mm
  const auto net = test::network_from("model p { spring e (k = 50) friction f (k = 400, fy = 12) }", "p");
  const auto h = runtime::run_history(net, runtime::static_triangle({amplitude}, 0.05, 2, 400), false);
  // Second cycle, steady: from the turning point at -A rising, F_f = min(fy, -fy + k (u + A)), etc.
  double worst = 0.0;
  for (std::size_t i = 401; i < h.time.size(); ++i) {
    const double u = h.displacement[i], du = u - h.displacement[i - 1];
    // Branch: rising after -A, falling after +A.
    const double friction = du > 0 ? std::min(fy, -fy + k * (u + amplitude)) : std::max(-fy, fy - k * (amplitude - u));
    worst = std::max(worst, std::abs(h.force[i] - (ke * u + friction)));
  }
  CHECK(worst < 1e-10);
}

TEST_CASE("slider in series with a Maxwell element matches the hand-derived solution") {
  // Stuck: F = c v (1 - exp(-t/tau)) until F = fy; then the slider slips at F = fy.
  // Reversed: F = (fy + c v) exp(-s/tau) - c v until F = -fy.
  const double k = 50, tau = 0.1, c = k * tau, v = 2, fy = 6;
  const auto net = test::network_from("model s { series { slider s (fy = 6) maxwell m (k = 50, tau = 0.1 s) } }", "s");
  runtime::Drive d;
  const double dt = 1e-3;
  for (int i = 0; i <= 600; ++i) {
    const double t = i * dt;
    d.time.push_back(t);
    d.displacement.push_back(t <= 0.3 ? v * t : v * 0.3 - v * (t - 0.3));
  }
  const auto h = runtime::run_history(net, d, true);
  double worst = 0.0;
  for (std::size_t i = 1; i < h.time.size(); ++i) {
    const double t = h.time[i];
    double expected;
    if (t <= 0.3 + 1e-12) {
      expected = std::min(fy, c * v * (1 - std::exp(-t / tau)));
    } else {
      const double s = t - 0.3;
      expected = std::max(-fy, (fy + c * v) * std::exp(-s / tau) - c * v);
    }
    worst = std::max(worst, std::abs(h.force[i] - expected));
  }
  CHECK(worst < 1e-9);
  // Element outputs: the slider carries the chain force; elongations add up to the drive.
  for (std::size_t i = 1; i < h.time.size(); i += 50) {
    CHECK(std::abs(h.element_force[0][i] - h.force[i]) < 1e-12);
    CHECK(std::abs(h.element_elongation[0][i] + h.element_elongation[1][i] - h.displacement[i]) < 1e-12);
  }
}

TEST_CASE("step() is pure: the same state and drive give the same result") {
  const auto net = test::network_from("model s { spring e (k = 10) series { friction f (k = 30, fy = 2) maxwell m (k = 5, tau = 3 ms) } }", "s");
  const runtime::Simulator sim(net);
  const auto plan = runtime::StepPlan::make(net, 1e-3);
  runtime::State a = sim.rest_state(), b = a, c = a;
  const double f1 = sim.step(plan, a, 0.1, b);
  const double f2 = sim.step(plan, a, 0.1, c);
  CHECK(f1 == f2);
  CHECK(b.values == c.values);
}

TEST_CASE("element outputs of inerter, quadratic_dashpot, bouc_wen and gap") {
  // Root-block elements have the drive as elongation; a chain's members carry its force and
  // their elongations add up to the drive; the branch forces add up to the total.
  const auto net = test::network_from(R"(
    model e { inerter m (b = 1 kg) quadratic_dashpot q (cq = 0.01 N*s^2/mm^2) bouc_wen w (k = 100, n = 2, fy = 3)
              series { gap g (width = 0.1 mm) spring s (k = 40) } })",
                                      "e");
  const auto h = runtime::run_history(net, runtime::quasistatic_sine({0.3}, 2.0, 1, 200), true, runtime::SolverChoice::fixed);
  REQUIRE(h.element_paths == std::vector<std::string>{"m", "q", "w", "g", "s"});
  for (std::size_t i = 1; i < h.time.size(); ++i) {
    const double u = h.displacement[i], du = u - h.displacement[i - 1], dt = h.time[i] - h.time[i - 1];
    for (std::size_t j = 0; j < 3; ++j) CHECK(std::abs(h.element_elongation[j][i] - u) < 1e-12);
    CHECK(std::abs(h.element_force[1][i] - 0.01 * std::abs(du / dt) * du / dt) < 1e-12);
    CHECK(std::abs(h.element_force[2][i]) < 3.0);
    CHECK(h.element_force[3][i] == h.element_force[4][i]);
    CHECK(std::abs(h.element_force[4][i] - 40.0 * h.element_elongation[4][i]) < 1e-11);  // the solve tolerance
    CHECK(std::abs(h.element_elongation[3][i] + h.element_elongation[4][i] - u) < 1e-12);
    CHECK(std::abs(h.element_elongation[3][i]) <= 0.05);
    CHECK(std::abs(h.element_force[0][i] + h.element_force[1][i] + h.element_force[2][i] + h.element_force[3][i] - h.force[i]) < 1e-12);
  }
}

TEST_CASE("an inerter driven directly: a rate change gives a force pulse of impulse b dr over two steps") {
  // Ramp from rest at rate r: the force is b (2 r, -r, 0, ...)/dt (the three-rate rule with
  // rates 0, 0 before the drive began), so its impulse sum F dt is b r, and it is zero while
  // the rate is constant. Reversal to -r: b (-4 r, 2 r, 0)/dt, impulse -2 b r.
  const double b = 2e-3, r = 5.0, dt = 1e-3;
  const auto net = test::network_from("model i { inerter m (b = 2 kg) }", "i");
  runtime::Drive d;
  for (int i = 0; i <= 20; ++i) {
    d.time.push_back(i * dt);
    d.displacement.push_back(i <= 10 ? r * i * dt : r * (20 - i) * dt);
  }
  const auto h = runtime::run_history(net, d, false, runtime::SolverChoice::fixed);
  const double expected[] = {0, 2, -1, 0, 0, 0, 0, 0, 0, 0, 0, -4, 2, 0, 0, 0, 0, 0, 0, 0, 0};
  for (std::size_t i = 0; i < h.time.size(); ++i) CHECK(std::abs(h.force[i] - expected[i] * b * r / dt) < 1e-9);
}

}  // namespace simulator_test
