// Nested series/parallel subtrees against hand-derived piecewise-linear solutions.
#include "runtime/stepping/tree_solver.hpp"

#include "runtime/protocols/run_history.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/stepping/drive_stepper.hpp"
#include "runtime/stepping/simulator.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace tree_solver_test {

using namespace rheo;

namespace {
runtime::History ramp(const runtime::Network& net, double to, int steps) {
  runtime::Drive d;
  for (int i = 0; i <= steps; ++i) {
    d.time.push_back(i * 0.01);
    d.displacement.push_back(to * i / steps);
  }
  return runtime::run_history(net, d, false);
}
}  // namespace

TEST_CASE("springs in series: k1 k2 / (k1 + k2)") {
  const auto net = test::network_from("model s { series { spring a (k = 300) spring b (k = 600) } }", "s");
  const auto h = ramp(net, 1.0, 10);
  for (std::size_t i = 0; i < h.time.size(); ++i) CHECK(std::abs(h.force[i] - 200.0 * h.displacement[i]) < 1e-9);
}

TEST_CASE("sliders in series slip at the weakest slip force") {
  const auto net = test::network_from("model s { spring e (k = 1) series { slider a (fy = 7) slider b (fy = 3) } }", "s");
  const auto h = ramp(net, 2.0, 8);
  for (std::size_t i = 1; i < h.time.size(); ++i) CHECK(std::abs(h.force[i] - (h.displacement[i] + 3.0)) < 1e-12);
}

TEST_CASE("spring in series with a parallel spring + friction block") {
  // Elastic: F = k0 (k1 + k2) / (k0 + k1 + k2) u until k2 e_p = fy; then F = k0 (u - e_p) with
  // e_p = (k0 u - fy) / (k0 + k1).
  const double k0 = 200, k1 = 50, k2 = 150, fy = 3;
  const auto net = test::network_from("model s { series { spring a (k = 200) parallel { spring b (k = 50) friction f (k = 150, fy = 3) } } }", "s");
  const auto h = ramp(net, 0.2, 40);
  for (std::size_t i = 0; i < h.time.size(); ++i) {
    const double u = h.displacement[i];
    const double elastic = k0 * (k1 + k2) / (k0 + k1 + k2) * u;
    const double ep_elastic = elastic / (k1 + k2);
    const double f = k2 * ep_elastic <= fy ? elastic : k0 * (u - (k0 * u - fy) / (k0 + k1));
    CHECK(std::abs(h.force[i] - f) < 1e-9);
  }
}

TEST_CASE("spring in series with a parallel slider + spring block (rigid until it slips)") {
  const double k0 = 100, k1 = 20, fy = 5;
  const auto net = test::network_from("model s { series { spring a (k = 100) parallel { slider s (fy = 5) spring b (k = 20) } } }", "s");
  const auto h = ramp(net, 0.3, 30);
  for (std::size_t i = 0; i < h.time.size(); ++i) {
    const double u = h.displacement[i];
    const double f = k0 * u <= fy ? k0 * u : k0 * (u - (k0 * u - fy) / (k0 + k1));
    CHECK(std::abs(h.force[i] - f) < 1e-9);
  }
}

TEST_CASE("two friction elements in series act as one with k = k1 k2/(k1 + k2) and fy = min") {
  const auto chain = test::network_from("model s { series { friction a (k = 300, fy = 9) friction b (k = 600, fy = 4) } }", "s");
  const auto single = test::network_from("model s { friction a (k = 200, fy = 4) }", "s");
  const auto drive = runtime::quasistatic_sine({0.1, 0.03}, 1.0, 2, 64);
  const auto a = runtime::run_history(chain, drive, false), b = runtime::run_history(single, drive, false);
  for (std::size_t i = 0; i < a.time.size(); ++i) CHECK(std::abs(a.force[i] - b.force[i]) < 1e-9);
}

// ---- gap, quadratic_dashpot and inerter in series chains.

namespace {
using runtime::SolverChoice;

// A triangle 0 -> A -> -A -> ... at velocity v sampled every dt, from rest.
runtime::Drive triangle(double amplitude, double velocity, int cycles, int steps_per_cycle) {
  return runtime::static_triangle({amplitude}, velocity, cycles, steps_per_cycle);
}
}  // namespace

TEST_CASE("spring in series with a gap over full cycles: F = 0 within the play, k (u -+ h) beyond") {
  // The spring is elastic, so the gap sits at u within the play and at +-h beyond it:
  // F = k (u - clamp(u, -h, h)), exact (zero within the play) at every sample.
  const double k = 50, h = 0.1;
  const auto net = test::network_from("model g { series { gap play (width = 0.2 mm) spring s (k = 50) } }", "g");
  const auto drive = triangle(0.5, 5.0, 2, 64);  // samples every 0.03125 mm: play edges are crossed inside steps
  const auto hist = runtime::run_history(net, drive, true);
  REQUIRE(hist.element_paths.size() == 2);
  int inside = 0;
  for (std::size_t i = 0; i < hist.time.size(); ++i) {
    const double u = hist.displacement[i], gap = std::clamp(u, -h, h);
    CAPTURE(u);
    if (std::abs(u) < h) {
      CHECK(hist.force[i] == 0.0);
      ++inside;
    }
    CHECK(std::abs(hist.force[i] - k * (u - gap)) < 1e-11);        // of F^ = 20 N
    CHECK(std::abs(hist.element_elongation[0][i] - gap) < 1e-13);  // the gap
    CHECK(std::abs(hist.element_force[0][i] - hist.force[i]) < 1e-13);
    CHECK(std::abs(hist.element_elongation[1][i] - hist.force[i] / k) < 1e-13);  // the spring
  }
  CHECK(inside > 10);
}

TEST_CASE("bump stop: a spring in series with (spring || gap + spring), a gap inside a parallel block's chain") {
  // Elastic, so F(u) is piecewise linear: the block's elongation x is k_a u/(k_a + k_b) while
  // |x| <= h, and (k_a u +- k_c h)/(k_a + k_b + k_c) beyond; F = k_a (u - x).
  const double ka = 300, kb = 20, kc = 500, h = 0.1;
  const auto net = test::network_from(
      "model b { series { spring a (k = 300) parallel { spring b (k = 20) series { gap g (width = 0.2 mm) spring c (k = 500) } } } }", "b");
  const auto hist = runtime::run_history(net, triangle(2.0, 10.0, 2, 96), false);
  for (std::size_t i = 0; i < hist.time.size(); ++i) {
    const double u = hist.displacement[i];
    double x = ka * u / (ka + kb);
    if (std::abs(x) > h) x = (ka * u + std::copysign(kc * h, u)) / (ka + kb + kc);
    CAPTURE(u);
    CHECK(std::abs(hist.force[i] - ka * (u - x)) < 1e-10);
  }
}

namespace {
// Exact event-driven solution of series { gap (half-width h); maxwell (k, tau) } under a
// piecewise-linear drive: within the play F = 0 and the Maxwell element holds its elongation;
// at a stop F' = k u' - F/tau until F returns to 0 (contact lost) while moving away.
std::vector<double> gap_maxwell_reference(const runtime::Drive& d, double h, double k, double tau) {
  const double c = k * tau;
  double gap = 0.0, force = 0.0;
  std::vector<double> out{0.0};
  for (std::size_t i = 1; i < d.time.size(); ++i) {
    const double v = (d.displacement[i] - d.displacement[i - 1]) / (d.time[i] - d.time[i - 1]);
    double rest = d.time[i] - d.time[i - 1];
    while (rest > 0.0) {
      const bool contact = force != 0.0 || (gap >= h && v > 0.0) || (gap <= -h && v < 0.0);
      if (!contact) {
        const double to_stop = v > 0.0 ? (h - gap) / v : v < 0.0 ? (-h - gap) / v : rest;
        const double t = std::min(rest, to_stop);
        gap = t == to_stop ? (v > 0.0 ? h : -h) : gap + v * t;
        rest -= t;
        continue;
      }
      // F(t) = (F0 - c v) e^{-t/tau} + c v; it returns to 0 when c v has the other sign.
      double t = rest;
      if (force * v < 0.0) t = std::min(rest, tau * std::log((force - c * v) / (-c * v)));
      force = t == rest ? (force - c * v) * std::exp(-t / tau) + c * v : 0.0;
      rest -= t;
    }
    out.push_back(force);
  }
  return out;
}
}  // namespace

TEST_CASE("gap in series with a Maxwell element: the event-driven exact solution, second order at contact events") {
  // Between events the chain is exact. A contact made at a fraction phi of a step spreads the
  // Maxwell increment v (1 - phi) dt over the whole step: the force is off by
  // k v dt^2 phi (1 - phi) / (2 tau) <= k v dt^2 / (8 tau), which then relaxes. Observed worst
  // errors 0.030, 0.011, 0.0017 N at 100, 200, 400 steps per cycle against that bound's 0.049,
  // 0.012, 0.0031 N (v = w u0); checked against 1.5x the bound. Within the play F = 0 exactly.
  const double h = 0.1, k = 50, tau = 0.02, u0 = 0.5, f = 2.0;
  const auto net = test::network_from("model g { series { gap play (width = 0.2 mm) maxwell m (k = 50, tau = 20 ms) } }", "g");
  for (int steps : {100, 200, 400}) {
    const auto drive = runtime::quasistatic_sine({u0}, f, 3, steps);
    const auto hist = runtime::run_history(net, drive, true);
    const auto reference = gap_maxwell_reference(drive, h, k, tau);
    double worst = 0.0;
    int zero = 0;
    for (std::size_t i = 0; i < hist.time.size(); ++i) {
      worst = std::max(worst, std::abs(hist.force[i] - reference[i]));
      if (reference[i] == 0.0 && std::abs(hist.element_elongation[0][i]) < h - 0.01) {
        CHECK(hist.force[i] == 0.0);
        ++zero;
      }
    }
    const double dt = 1.0 / (f * steps), bound = k * (2 * std::numbers::pi * f * u0) * dt * dt / (8.0 * tau);
    MESSAGE(steps << " steps per cycle: worst force error " << worst << " N, bound " << bound << " N");
    CHECK(zero > 10);
    CHECK(worst < 1.5 * bound);
  }
}

namespace {
// Reference for series { spring k; quadratic_dashpot cq } under a piecewise-linear drive:
// x' = sgn(F) sqrt(|F|/cq), F = k (u - x), by RK4 with `substeps` per drive interval.
std::vector<double> spring_quadratic_dashpot_reference(const runtime::Drive& d, double k, double cq, int substeps) {
  double x = 0.0;
  std::vector<double> out{0.0};
  for (std::size_t i = 1; i < d.time.size(); ++i) {
    const double t0 = d.time[i - 1], h = (d.time[i] - t0) / substeps;
    const double u0 = d.displacement[i - 1], v = (d.displacement[i] - u0) / (d.time[i] - t0);
    auto rate = [&](double t, double xx) {
      const double f = k * (u0 + v * (t - t0) - xx);
      return std::copysign(std::sqrt(std::abs(f) / cq), f);
    };
    for (int s = 0; s < substeps; ++s) {
      const double t = t0 + s * h;
      const double r1 = rate(t, x), r2 = rate(t + h / 2, x + h / 2 * r1), r3 = rate(t + h / 2, x + h / 2 * r2), r4 = rate(t + h, x + h * r3);
      x += h / 6 * (r1 + 2 * r2 + 2 * r3 + r4);
    }
    out.push_back(k * (d.displacement[i] - x));
  }
  return out;
}
}  // namespace

TEST_CASE("spring in series with a quadratic dashpot: an RK4 reference, first order in the step") {
  // The quadratic dashpot's relation is exact for a constant rate; behind an internal node the
  // rate varies within a step, so the chain is first order like a linear dashpot there (and
  // the dashpot dominates here: its compliance is infinite at F = 0). Observed worst errors
  // 0.048, 0.026, 0.013 N (of F^ = 2.36 N) at 400, 800, 1600 steps per cycle (0.16 N at 100);
  // the reference's own error (200 RK4 substeps per interval) is below 1e-6 N. Tolerance 3x at
  // 400, and the error must halve with the step (ratio within [1.7, 2.3]); one step a sample
  // (DriveStepper's tolerance 0). A history run (its error control, drive_stepper.hpp) at 400:
  // within 0.15 times that.
  const double k = 40, cq = 0.01;
  const auto net = test::network_from("model q { series { spring s (k = 40) quadratic_dashpot q (cq = 0.01 N*s^2/mm^2) } }", "q");
  double previous = 0.0;
  for (int steps : {400, 800, 1600}) {
    const auto drive = runtime::quasistatic_sine({0.5}, 5.0, 2, steps);
    const auto reference = spring_quadratic_dashpot_reference(drive, k, cq, 200);
    runtime::DriveStepper stepper(net, true, 0.0);
    double worst = 0.0, peak = 0.0;
    for (std::size_t i = 0; i < drive.time.size(); ++i) {
      const double force = i == 0 ? stepper.start(drive.time[0], drive.displacement[0]) : stepper.step(drive.time[i], drive.displacement[i]);
      worst = std::max(worst, std::abs(force - reference[i]));
      peak = std::max(peak, std::abs(reference[i]));
      // Both members carry the chain force; their elongations add up to the drive.
      CHECK(std::abs(stepper.element_force()[1] - force) < 1e-12);
      CHECK(std::abs(stepper.element_elongation()[0] + stepper.element_elongation()[1] - drive.displacement[i]) < 1e-12);
    }
    MESSAGE(steps << " steps per cycle: worst force error " << worst << " N of F^ = " << peak << " N");
    if (previous == 0.0) {
      CHECK(worst < 0.15);
      const auto controlled = runtime::run_history(net, drive, true);
      double controlled_worst = 0.0;
      for (std::size_t i = 0; i < drive.time.size(); ++i) {
        controlled_worst = std::max(controlled_worst, std::abs(controlled.force[i] - reference[i]));
        CHECK(std::abs(controlled.element_force[1][i] - controlled.force[i]) < 1e-12);
        CHECK(std::abs(controlled.element_elongation[0][i] + controlled.element_elongation[1][i] - drive.displacement[i]) < 1e-12);
      }
      MESSAGE("controlled: worst force error " << controlled_worst << " N");
      CHECK(controlled_worst < 0.15 * worst);  // 0.0043 N against 0.048 N
    } else {
      CHECK(previous / worst == doctest::Approx(2.0).epsilon(0.15));
    }
    previous = worst;
  }
}

TEST_CASE("spring in series with an inerter: Newmark is second order and conserves the oscillator's energy") {
  // b x'' = k (u - x), a ramp to u0 over T then a hold (w = sqrt(k/b) = 316 rad/s):
  //   ramp  x = V t - (V/w) sin(w t),   V = u0/T,
  //   hold  x = u0 + (x_T - u0) cos(w s) + (x'_T/w) sin(w s),  s = t - T;   F = k (u - x).
  // Newmark's relative frequency error (w dt)^2/12 accumulates as a phase error: observed worst
  // force errors over 10 periods, at dt = 0.1 ms and 0.05 ms, fall 4x per halving (checked in
  // [3.6, 4.4]; observed 0.065 and 0.016 N of 20 N); in the hold, b v^2/2 + F^2/(2k) is
  // Newmark's exact invariant (no numerical damping), constant to rounding.
  const double k = 100, b = 1e-3, u0 = 0.2, rise = 0.01, w = std::sqrt(k / b);
  const auto net = test::network_from("model m { series { spring s (k = 100) inerter m (b = 1 kg) } }", "m");
  auto exact = [&](double t) {
    const double v = u0 / rise;
    if (t <= rise) return k * (v * t - (v * t - v / w * std::sin(w * t)));
    const double x = v * rise - v / w * std::sin(w * rise), xd = v * (1 - std::cos(w * rise)), s = t - rise;
    return k * (u0 - (u0 + (x - u0) * std::cos(w * s) + xd / w * std::sin(w * s)));
  };
  double previous = 0.0;
  for (double dt : {1e-4, 5e-5}) {
    const auto hist = runtime::run_history(net, runtime::step_relaxation(u0, rise, 0.2, dt), false, SolverChoice::fixed);
    double worst = 0.0;
    for (std::size_t i = 0; i < hist.time.size(); ++i) worst = std::max(worst, std::abs(hist.force[i] - exact(hist.time[i])));
    MESSAGE("dt = " << dt << " s: worst force error " << worst << " N of " << k * u0 << " N");
    if (previous > 0.0) {
      CHECK(previous / worst > 3.6);
      CHECK(previous / worst < 4.4);
    }
    previous = worst;
  }
  // Energy in the hold, from the state: the inerter's velocity is its third slot.
  const runtime::Simulator sim(net);
  const auto plan = runtime::StepPlan::make(net, 1e-4);
  runtime::State state = sim.rest_state(), next = state;
  const auto& t = net.topology();
  const runtime::TreeNode* inerter = nullptr;
  for (const auto& node : t.nodes)
    if (node.kind == runtime::NodeKind::inerter) inerter = &node;
  REQUIRE(inerter);
  CHECK(inerter->slots == 3);
  double e_min = 1e300, e_max = 0.0;
  for (int n = 1; n <= 2000; ++n) {
    const double force = sim.step(plan, state, std::min(1.0, n * 1e-4 / rise) * u0, next);
    std::swap(state, next);
    const double v = state.values[static_cast<std::size_t>(inerter->state + 2)];
    const double energy = 0.5 * b * v * v + 0.5 * force * force / k;
    if (n * 1e-4 > rise + 1e-12) e_min = std::min(e_min, energy), e_max = std::max(e_max, energy);
  }
  MESSAGE("hold energy " << e_max << " N*mm, relative spread " << (e_max - e_min) / e_max);
  // Rounding of the elongation increments (~1e-17 mm) is amplified by 4 b/dt^2 = 4e5 N/mm:
  // observed drift 2.3e-9 over 1900 steps; a damped scheme would lose orders of magnitude more.
  CHECK((e_max - e_min) / e_max < 1e-8);
  CHECK(e_max > 0.01);
}

TEST_CASE("capped-linear chains and linear blocks: the closed-form step equals the iterative solve") {
  // The same chain twice: with springs, it takes the closed-form step (tree_solver.hpp: F =
  // clamp(F0 + S de, cap)); with each spring written as a yeoh of D10 = k/2, D20 = D30 = 0,
  // no node is linear and every step is solved by the nested Newton iterations.
  const std::string chain = R"(model m {
    spring rubber (k = 300 N/mm)
    series fluid {
      slider cap (fy = 40 N)
      friction f (k = 900 N/mm, fy = 60 N)
      SPRING_A
      parallel y {
        inerter column (b = 20 kg)
        maxwell arm (k = 2000 N/mm, tau = 2 ms)
        SPRING_B
        series bulge { SPRING_C  spring k3 (k = 400 N/mm) }
      }
    }
  })";
  auto model = [&](bool linear) {
    std::string text = chain;
    const char* names[] = {"SPRING_A", "SPRING_B", "SPRING_C"};
    const double k[] = {500.0, 150.0, 250.0};
    for (int i = 0; i < 3; ++i) {
      const std::string element = linear ? "spring s" + std::to_string(i) + " (k = " + std::to_string(k[i]) + " N/mm)"
                                         : "yeoh s" + std::to_string(i) + " (D10 = " + std::to_string(k[i] / 2) +
                                               " N/mm, D20 = 0 N/mm^3, D30 = 0 N/mm^5)";
      text.replace(text.find(names[i]), std::string(names[i]).size(), element);
    }
    return test::network_from(text, "m");
  };
  const auto fast = model(true), iterative = model(false);
  const auto& nodes = fast.topology().nodes;
  CHECK(std::any_of(nodes.begin(), nodes.end(), [](const runtime::TreeNode& n) { return n.capped_linear; }));
  CHECK(std::none_of(iterative.topology().nodes.begin(), iterative.topology().nodes.end(),
                     [](const runtime::TreeNode& n) { return n.capped_linear || (n.linear && n.child_count > 0); }));
  // Small amplitudes stick, large ones slip the cap (and the friction element's 60 N is never reached).
  const runtime::Drive drive = runtime::quasistatic_sine({0.02, 0.3, 1.5}, 15.0, 2, 64);
  const auto a = runtime::run_history(fast, drive, false, runtime::SolverChoice::fixed);
  const auto b = runtime::run_history(iterative, drive, false, runtime::SolverChoice::fixed);
  REQUIRE(a.force.size() == b.force.size());
  double worst = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < a.force.size(); ++i) {
    worst = std::max(worst, std::abs(a.force[i] - b.force[i]));
    peak = std::max(peak, std::abs(a.force[i]));
  }
  MESSAGE("worst force difference " << worst << " N of " << peak << " N");
  CHECK(peak > 300.0 * 1.5 + 40.0 * 0.9);  // the cap slipped at the largest amplitude
  CHECK(worst < 1e-9 * peak);
}

TEST_CASE("a softening yeoh: the tangent's zero in closed form, and in series a force beyond its peak is an error naming it") {
  // slope = 2 D10 + 12 D20 e^2 + 30 D30 e^4 (eq. 3.3).
  const runtime::YeohLaw cubic{1.0, -1.0, 0.0};  // e*^2 = 2/12
  CHECK(cubic.softening_elongation() == doctest::Approx(std::sqrt(1.0 / 6.0)).epsilon(1e-14).scale(0.0));
  const runtime::YeohLaw quintic{10.0, -3.0, 0.1};  // D20^2 = 9 > (5/3) 10 0.1: softens
  const double e = quintic.softening_elongation();
  CHECK(std::abs(quintic.slope(e)) < 1e-12 * 20.0);
  CHECK(quintic.slope(0.99 * e) > 0.0);
  CHECK(quintic.slope(1.01 * e) < 0.0);
  CHECK(std::isinf(runtime::YeohLaw{53.4938, -0.1648, 0.0015}.softening_elongation()));  // specimen A stiffens again
  CHECK(std::isinf(runtime::YeohLaw{10.0, -1.0, 0.1}.softening_elongation()));           // D20^2 = 1 < 5/3
  CHECK(std::isfinite(runtime::YeohLaw{10.0, 1.0, -0.1}.softening_elongation()));        // D30 < 0 always turns over

  // Peak force of the cubic: F(e*) = 2 e* - 4 e*^3 = 0.5443 N. A 1 N/mm spring in series.
  const auto net = test::network_from("model y { series { yeoh r (D10 = 1, D20 = -1, D30 = 0) spring s (k = 1) } }", "y");
  const double peak = 2.0 * std::sqrt(1.0 / 6.0) - 4.0 * std::pow(1.0 / 6.0, 1.5);
  const auto below = ramp(net, 0.6, 60);  // e_yeoh < e* all along: F = 2 e - 4 e^3, u = e + F
  for (std::size_t i = 0; i < below.time.size(); ++i) {
    const double f = below.force[i];
    CHECK(f < peak);
    const double e_yeoh = below.displacement[i] - f;
    CHECK(std::abs(2.0 * e_yeoh - 4.0 * e_yeoh * e_yeoh * e_yeoh - f) < 1e-9);
  }
  CHECK_THROWS_WITH_AS(ramp(net, 2.0, 60), doctest::Contains("yeoh 'r' is asked to carry"), runtime::NumericalError);
}

TEST_CASE("an exhausted iteration cap is a NumericalError naming the block and the time, not a hang") {
  // A yeoh spring in series with a spring needs an iterative chain solve; with the cap lowered
  // to one refinement (of the nested solve and of the global Newton solve, which falls back to
  // it) it cannot converge, and the step says where and when. A fresh plan: the Newton solve
  // starts from the plan's last step, which would be this step's answer.
  const auto net = test::network_from("model y { series c { yeoh r (D10 = 1, D20 = 0.5, D30 = 0.1) spring s (k = 2) } }", "y");
  const runtime::Simulator simulator(net);
  runtime::State before = simulator.rest_state(), after = before;
  CHECK(std::isfinite(simulator.step(runtime::StepPlan::make(net, 0.01), before, 1.5, after, 0.25)));
  runtime::StepPlan plan = runtime::StepPlan::make(net, 0.01);
  plan.tree.iteration_cap = 1;
  CHECK_THROWS_WITH_AS(simulator.step(plan, before, 1.5, after, 0.25),
                       doctest::Contains("did not converge within its iteration cap in the step ending at t = 0.25 s"), runtime::NumericalError);
  CHECK_THROWS_WITH_AS(simulator.step(plan, before, 1.5, after, 0.25), doctest::Contains("model 'y'"), runtime::NumericalError);
}

TEST_CASE("bouc_wen with n < 0.5 behind a gap and a spring: every history ends with a result") {
  // The pathological family of issue #26 (n = 0.05 and 0.3, increments of hundreds of yield
  // displacements that saturate the law): each run ends, with |F| within fy. (Nested inside a
  // parallel block the same runs end too, but cost ~10 s each: issue #26 item 3, left open.)
  for (const char* n : {"0.05", "0.3"}) {
    const auto net = test::network_from(
        std::string("model m { series { gap g (width = 4 mm) spring s (k = 5000) bouc_wen b (k = 30000, n = ") + n + ", fy = 1600) } }", "m");
    runtime::Drive d;
    d.time = {0.0, 0.1, 0.2, 0.3, 0.4, 0.5};
    d.displacement = {0.0, 5.0, 20.0, -20.0, 2.0, 0.0};
    const auto h = runtime::run_history(net, d, false, runtime::SolverChoice::fixed);
    for (double f : h.force) CHECK(std::abs(f) <= 1600.0);
    CHECK(h.force[2] > 1599.0);
    CHECK(h.force[3] < -1599.0);
  }
}

TEST_CASE("the nested solve: a spring in series with a saturated bouc_wen carries k e, the bouc_wen takes the rounding remainder") {
  // Near saturation the bouc_wen's elongation is ill-conditioned in the chain's force (dF/de -> 0):
  // the member that takes the chain's rounding remainder must be the most compliant one, else
  // the spring is stretched beyond fy/k while the chain carries fy. The global Newton solve is
  // switched off: this is the nested solve, its fallback and second path.
  const auto net = test::network_from(
      "model m { series { bouc_wen b (k = 143.159, n = 2.65461, uy = 15.6271 um) spring s (k = 32.3676) } dashpot (c = 0.0880497) }", "m");
  const runtime::Simulator simulator(net);
  runtime::StepPlan plan = runtime::StepPlan::make(net, 5e-4);
  plan.tree.global_newton = false;
  runtime::State a = simulator.rest_state(), b = a;
  std::vector<double> force, elongation;
  const double fy = 143.159 * 15.6271e-3;
  double worst = 0.0;
  for (int k = 1; k <= 400; ++k) {
    const double u = 0.4 * std::sin(2 * std::numbers::pi * 5 * 5e-4 * k);
    (void)simulator.step(plan, a, u, b);
    simulator.element_outputs(plan, a, b, force, elongation);
    worst = std::max(worst, std::abs(force[1] - 32.3676 * elongation[1]));
    CHECK(std::abs(force[1]) <= fy * (1 + 1e-12));
    std::swap(a, b);
  }
  MESSAGE("worst |F_s - k e_s| = " << worst << " N");
  CHECK(worst < 1e-12 * fy);
}

}  // namespace tree_solver_test
