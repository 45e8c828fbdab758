// Harmonic protocol against the closed forms of Appendices B and C, through both ways of finding
// the periodic state: time stepping and the closed form of periodic_closed_form.hpp.
// Required accuracy: relative error <= 1e-5 in stiffness, <= 1e-3 deg in phase.
#include "runtime/harmonic.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>

using namespace rheo;
using runtime::HarmonicDefinition;
using runtime::HarmonicOptions;
using test::degrees;
using test::relative_error;

namespace {

constexpr double kStiffnessTolerance = 1e-5;
constexpr double kPhaseToleranceDeg = 1e-3;

void check_point(const runtime::Network& net, double u0, double f, double stiffness, double phase_rad,
                 HarmonicDefinition definition = HarmonicDefinition::thesis) {
  for (auto steady_state : {runtime::SteadyState::time_stepping, runtime::SteadyState::closed_form}) {
    HarmonicOptions options;
    options.definition = definition;
    options.steady_state = steady_state;
    const auto p = runtime::simulate_harmonic_point(net, u0, f, options);
    CAPTURE(u0);
    CAPTURE(f);
    CAPTURE(static_cast<int>(steady_state));
    CHECK(p.converged);
    CHECK(relative_error(p.measures.stiffness, stiffness) <= kStiffnessTolerance);
    CHECK(std::abs(degrees(p.measures.phase - phase_rad)) <= kPhaseToleranceDeg);
  }
}

void check_linear(const runtime::Network& net, double u0, double f, std::complex<double> k_star) {
  check_point(net, u0, f, std::abs(k_star), std::arg(k_star), HarmonicDefinition::thesis);
  check_point(net, u0, f, std::abs(k_star), std::arg(k_star), HarmonicDefinition::first_harmonic);
}

}  // namespace

TEST_CASE("Kelvin-Voigt: E_dyn = sqrt(k^2 + c^2 w^2), tan(delta) = c w / k (B.47-B.49)") {
  const auto net = test::network_from("model kv { spring s (k = 172.29) dashpot d (c = 0.0953 N*s/mm) }", "kv");
  const double k = 172.29, c = 0.0953;
  for (double f : {0.5, 5.0, 49.0}) {
    const double w = 2 * std::numbers::pi * f;
    check_linear(net, 0.6, f, {k, c * w});
  }
}

TEST_CASE("Zener: K* = K_e + K_v i w t_r / (1 + i w t_r) (B.69, C.6)") {
  const auto net = test::network_from("model z { spring e (k = 905.41) maxwell m (k = 134.56, tau = 6.8 ms) }", "z");
  for (double f : {1.0, 23.0, 51.0}) {
    const double w = 2 * std::numbers::pi * f, tr = 6.8e-3;
    const std::complex<double> iwt{0.0, w * tr};
    check_linear(net, 1.0, f, 905.41 + 134.56 * iwt / (1.0 + iwt));
  }
}

TEST_CASE("generalized Maxwell (C.9), cylindrical bushing C of Table D.3") {
  const auto net = test::network_from(R"(
    model gm {
      spring  e  (k = 490.629)
      maxwell m1 (k = 111.5544, tau = 0.0013 s)
      maxwell m2 (k = 309.3259, tau = 0.5845 s)
      maxwell m3 (k = 143.1166, tau = 0.0157 s)
    })", "gm");
  const double kv[] = {111.5544, 309.3259, 143.1166}, tr[] = {0.0013, 0.5845, 0.0157};
  for (double f : {0.1, 3.0, 41.0}) {
    std::complex<double> k_star = 490.629;
    for (int j = 0; j < 3; ++j) {
      const std::complex<double> iwt{0.0, 2 * std::numbers::pi * f * tr[j]};
      k_star += kv[j] * iwt / (1.0 + iwt);
    }
    check_linear(net, 0.5, f, k_star);
  }
}

TEST_CASE("frictional Zener (C.15): stiffness K_e + K_p u_s / u0 above slip, damping U/(pi F^ u0)") {
  const double ke = 120.0, kp = 300.0, us = 0.05;  // fy = kp us = 15 N
  const auto net = test::network_from("model fz { spring e (k = 120) friction f (k = 300, uy = 50 um) }", "fz");
  for (double u0 : {0.02, 0.05, 0.08, 0.5, 3.0}) {
    const bool slips = u0 > us;
    const double f_hat = slips ? ke * u0 + kp * us : (ke + kp) * u0;
    const double energy = slips ? 4 * kp * us * (u0 - us) : 0.0;  // C.13
    const double d = energy / (std::numbers::pi * f_hat * u0);    // C.12
    check_point(net, u0, 7.0, f_hat / u0, std::asin(d));
  }
}

TEST_CASE("C.16 is the frictional part's damping: it matches the definition when K_e = 0") {
  const auto net = test::network_from("model f { friction f (k = 300, fy = 15) }", "f");
  // Beyond u0 = u_s / (1 - pi/4) a bare friction loop has d > 1; stay below.
  const double kp = 300, us = 0.05, u0 = 0.15;
  const double d = 4 * kp * us * (u0 - us) / (std::numbers::pi * u0 * kp * us);  // C.16 with C.13
  check_point(net, u0, 2.0, kp * us / u0, std::asin(d));                        // C.10
}

TEST_CASE("generalized frictional solid (C.17-C.20): elements yield one by one") {
  const auto net = test::network_from(R"(
    model gfs {
      spring   e  (k = 80)
      friction f1 (k = 1016.6, uy = 101.58 um)
      friction f2 (k = 301.04, uy = 42.256 um)
      friction f3 (k = 25.516, uy = 12.695 um)
    })", "gfs");
  const double kp[] = {1016.6, 301.04, 25.516}, us[] = {0.10158, 0.042256, 0.012695};
  for (double u0 : {0.01, 0.03, 0.07, 0.2, 1.5}) {
    double stiffness = 80.0, energy = 0.0;
    for (int j = 0; j < 3; ++j) {
      stiffness += u0 > us[j] ? kp[j] * us[j] / u0 : kp[j];             // C.17, C.18
      if (u0 > us[j]) energy += 4 * kp[j] * us[j] * (u0 - us[j]);      // C.20
    }
    const double d = energy / (std::numbers::pi * stiffness * u0 * u0);  // exact d = U / (pi F^ u0)
    check_point(net, u0, 11.0, stiffness, std::asin(d));
  }
  // With K_e = 0 and every element slipping, C.19 itself holds: d = sum U / (pi u0 sum K_p u_s).
  const auto bare = test::network_from("model b { friction f1 (k = 1016.6, uy = 101.58 um) friction f2 (k = 301.04, uy = 42.256 um) }", "b");
  const double u0 = 0.2, fsum = 1016.6 * 0.10158 + 301.04 * 0.042256;
  const double usum = 4 * 1016.6 * 0.10158 * (u0 - 0.10158) + 4 * 301.04 * 0.042256 * (u0 - 0.042256);
  check_point(bare, u0, 3.0, fsum / u0, std::asin(usum / (std::numbers::pi * u0 * fsum)));
}

TEST_CASE("steady state is detected from the first cycle when the periodic start is exact") {
  const auto net = test::network_from("model z { spring e (k = 100) maxwell m (k = 50, tau = 20 ms) friction f (k = 200, fy = 4) }", "z");
  HarmonicOptions options;
  options.steady_state = runtime::SteadyState::time_stepping;
  const auto p = runtime::simulate_harmonic_point(net, 0.3, 49.0, options);
  CHECK(p.converged);
  CHECK(p.cycles == 1);
}

TEST_CASE("a point that cannot reach steady state within the cycle budget says so") {
  // A spring in series with a slow dashpot (tau = 2 s) relaxes over hundreds of cycles from rest.
  const auto net = test::network_from("model s { spring e (k = 100) series { spring s (k = 50) dashpot d (c = 100) } }", "s");
  HarmonicOptions options;
  options.max_cycles = 2;
  const auto p = runtime::simulate_harmonic_point(net, 1.0, 10.0, options);
  CHECK_FALSE(p.converged);
  CHECK(p.cycles == 2);
  CHECK(p.residual > options.tolerance);
}
