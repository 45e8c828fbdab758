// IDA on the placements issue 26 left out of the differential test, against closed forms and
// extrapolated fixed steps: a bouc_wen inside a block, whose consistent rates come from a backward-Euler step
// (dae_initial_rates.cpp) because IDACalcIC holds the positions' rates fixed; two quadratic
// dashpots in series, whose rates the drive sets at once (IDACalcIC's line search failed at
// t = 0); a quadratic dashpot behind a very stiff spring from rest, where IDA's corrector fails
// at every step length until a backward-Euler step moves the rate off 0.
#include "runtime/dae/dae_protocols.hpp"
#include "runtime/protocols/run_history.hpp"
#include "support.hpp"
#include "two_tone_reference.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <numbers>

namespace dae_initial_rates_test {

using namespace rheo;

namespace {

runtime::History history(const std::string& source, const runtime::Drive& drive) {
  return runtime::dae_history(test::network_from(source, "m"), drive, false);
}

// Piecewise linear through (time, displacement) corners, sampled every `dt` [s].
runtime::Drive corners(std::initializer_list<std::pair<double, double>> points, double dt) {
  runtime::Drive d{{0.0}, {0.0}};
  double t0 = 0.0, u0 = 0.0;
  for (const auto& [t1, u1] : points) {
    const int n = static_cast<int>(std::lround((t1 - t0) / dt));
    for (int k = 1; k <= n; ++k) {
      d.time.push_back(t0 + (t1 - t0) * k / n);
      d.displacement.push_back(u0 + (u1 - u0) * k / n);
    }
    t0 = t1;
    u0 = u1;
  }
  return d;
}

// The root of an increasing function on [lo, hi] by bisection.
double solve_increasing(const std::function<double(double)>& f, double target, double lo, double hi) {
  for (int i = 0; i < 200; ++i) (f(0.5 * (lo + hi)) < target ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

}  // namespace

// Bouc-Wen with n = 1 loads as dz/de = (k/fy) (1 - |z|) and unloads as dz/de = k/fy, so a spring
// ks in series with it follows, from rest (F = fy z, e its elongation):
//   loading    u = F/ks + e_up(F),  e_up(F) = -(fy/k) ln(1 - F/fy)
//   unloading  u = u1 - (F1 - F)(1/ks + 1/k)                     while F >= 0 (from F1 at u1)
//   reloading  u = F/ks + e0 + (fy/k) ln(1 + F/fy)               for F < 0, e0 = e_up(F1) - F1/k
// The law reads the rate of the node between the two, which IDACalcIC held at its last value
// (0 at the start); the rates now come from a backward-Euler step at every restart: each 1 ms
// sample, the one at the peak with the drive's rate reversed.
TEST_CASE("a spring in series with bouc_wen (n = 1) up and back down: the piecewise closed form at every sample") {
  const double ks = 500.0, k = 200.0, fy = 10.0;  // N/mm, N/mm, N
  const auto h = history("model m { series { spring (k = 500 N/mm)\n bouc_wen (k = 200 N/mm, n = 1, fy = 10 N) } }",
                         corners({{0.05, 0.3}, {0.1, -0.1}}, 1e-3));
  const auto e_up = [&](double f) { return -(fy / k) * std::log1p(-f / fy); };
  const double u1 = 0.3;
  const double f1 = solve_increasing([&](double f) { return f / ks + e_up(f); }, u1, 0.0, fy * (1.0 - 1e-15));
  const double u_zero = u1 - f1 * (1.0 / ks + 1.0 / k), e0 = e_up(f1) - f1 / k;
  double worst = 0.0;
  for (std::size_t j = 0; j < h.time.size(); ++j) {
    const double u = h.displacement[j];
    double f = 0.0;
    if (h.time[j] <= 0.05) f = solve_increasing([&](double x) { return x / ks + e_up(x); }, u, 0.0, fy * (1.0 - 1e-15));
    else if (u >= u_zero) f = f1 - (u1 - u) / (1.0 / ks + 1.0 / k);
    else f = solve_increasing([&](double x) { return x / ks + e0 + (fy / k) * std::log1p(x / fy); }, u, -fy * (1.0 - 1e-15), 0.0);
    worst = std::max(worst, std::abs(h.force[j] - f));
  }
  CHECK(worst < 1e-6 * fy);  // observed 2.4e-7 fy (IDA's rtol 1e-8, global)
}

// Two bouc_wen in series (n = 1): no spring holds the node between them, whose balance is
// fy1 z1 = fy2 z2 alone; IDACalcIC's Newton matrix has no position column there. Loading from
// rest, the common force F gives u = e1(F) + e2(F), e_i = -(fy_i/k_i) ln(1 - F/fy_i).
TEST_CASE("two bouc_wen in series loaded from rest: u = sum of -(fy/k) ln(1 - F/fy)") {
  const double k1 = 960.0, fy1 = 8.6, k2 = 12.0, fy2 = 1.1;
  const auto h = history("model m { series { bouc_wen (k = 960 N/mm, n = 1, fy = 8.6 N)\n bouc_wen (k = 12 N/mm, n = 1, fy = 1.1 N) } }",
                         corners({{0.05, 0.4}}, 1e-3));
  const auto u_of = [&](double f) { return -(fy1 / k1) * std::log1p(-f / fy1) - (fy2 / k2) * std::log1p(-f / fy2); };
  double worst = 0.0;
  for (std::size_t j = 0; j < h.time.size(); ++j)
    worst = std::max(worst, std::abs(h.force[j] - solve_increasing(u_of, h.displacement[j], 0.0, fy2 * (1.0 - 1e-15))));
  CHECK(worst < 1e-6 * fy2);  // observed 3.8e-7 fy2
}

// Two quadratic dashpots in series (through a stuck slider, or directly) at a constant rate v
// share the force cq1 v1^2 = cq2 v2^2 with v1 + v2 = v: F = v^2 / (1/sqrt(cq1) + 1/sqrt(cq2))^2
// from the first instant (v_eps = 1e-3 mm/s changes it by below 1e-8 here). IDACalcIC's line
// search failed at t = 0 (IDA_LINESEARCH_FAIL); observed within 1e-6 at every sample.
TEST_CASE("two quadratic dashpots in series at a constant rate: F = v^2 / (1/sqrt(cq1) + 1/sqrt(cq2))^2") {
  const double cq1 = 0.00131465, cq2 = 0.00639128, v = 30.0;
  const double expected = v * v / std::pow(1.0 / std::sqrt(cq1) + 1.0 / std::sqrt(cq2), 2);
  for (const char* source : {"model m { series { quadratic_dashpot (cq = 0.00131465 N*s^2/mm^2)\n slider (fy = 50 N)\n"
                             " quadratic_dashpot (cq = 0.00639128 N*s^2/mm^2) } }",
                             "model m { series { quadratic_dashpot (cq = 0.00131465 N*s^2/mm^2)\n"
                             " quadratic_dashpot (cq = 0.00639128 N*s^2/mm^2) } }"}) {
    CAPTURE(source);
    const auto h = history(source, corners({{0.02, v * 0.02}}, 1e-3));
    for (std::size_t j = 1; j < h.time.size(); ++j) CHECK(h.force[j] == doctest::Approx(expected).epsilon(1e-6).scale(0.0));
  }
}

// A quadratic dashpot behind a spring 4 times stiffer, with a 37 times weaker dashpot, than
// dae_integrator_test's, on its two-tone drive from rest (30 mm/s, 1 ms samples): the rate w
// rises like sqrt(k v t / cq), which IDA's error test resolves only with steps so short that the
// corrector's tangent at w = 0 fails at every one; on IDA's own matrix it then stalled
// (IDA_TOO_MUCH_WORK at t = 6e-7 s). Against fixed steps at 64 and 128 steps per sample,
// extrapolated (2 F(128) - F(64)).
TEST_CASE("a quadratic dashpot behind a very stiff spring on a two-tone drive from rest agrees with extrapolated fixed steps") {
  const std::string source = "model m { series { quadratic_dashpot (cq = 0.000247703 N*s^2/mm^2)\n spring (k = 16089.8 N/mm) } }";
  const auto network = test::network_from(source, "m");
  const auto ida = runtime::dae_history(network, test::two_tone_drive(1), false);
  CHECK(test::gap_to_extrapolated_fixed_steps(network, ida.force) < 1e-6);  // observed 6.9e-10
}

// A quadratic dashpot and a dashpot behind a gap, driven at a constant rate v from rest: no force
// while the gap is open; once it closes, the two share the rate, cq v1^2 = c (v - v1), so
// F = c (v - v1), v1 = (sqrt(c^2 + 4 cq c v) - c) / (2 cq). At the contact IDACalcIC started
// from the rates of the open gap (the quadratic dashpot's at 0) and failed (IDA_CONV_FAIL); it
// now starts from those of a backward-Euler step.
TEST_CASE("a quadratic dashpot and a dashpot behind a gap that closes at a constant rate: F = c (v - v1)") {
  const double cq = 0.00737205, c = 0.312161, v = 30.0, contact = (-0.00858415 + 0.5 * 0.0259998) / v;  // s
  const double v1 = (std::sqrt(c * c + 4.0 * cq * c * v) - c) / (2.0 * cq);
  const auto h = history(
      "model m { series { quadratic_dashpot (cq = 0.00737205 N*s^2/mm^2)\n gap (width = 0.0259998 mm, center = -0.00858415 mm)\n"
      " dashpot (c = 0.312161 N*s/mm) } }",
      corners({{0.01, v * 0.01}}, 1e-4));
  for (std::size_t j = 0; j < h.time.size(); ++j) {
    CAPTURE(h.time[j]);
    if (h.time[j] < contact) CHECK(std::abs(h.force[j]) < 1e-9);
    else CHECK(h.force[j] == doctest::Approx(c * (v - v1)).epsilon(1e-6));
  }
}

}  // namespace dae_initial_rates_test
