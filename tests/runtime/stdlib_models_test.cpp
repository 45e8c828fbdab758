// Every standard-library model simulates as its header equation says: the linear ones against
// the phasor composition of their closed forms, the frictional ones against C.15-C.20, the
// parallel rate-dependent and rate-independent ones against their exact steady-state force
// waveform composed by hand, the slider-capped ones against their uncapped closed forms below
// the slip force and against the cap's force bound above it.
#include "lang/stdlib.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/closed_form/phasor.hpp"
#include "parallel_closed_form.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <complex>
#include <functional>

namespace stdlib_models_test {

using namespace rheo;

namespace {
runtime::HarmonicPoint point(const std::string& source, const std::string& model, double u0, double f) {
  return runtime::simulate_harmonic_point(test::network_from(source, model), u0, f, {});
}
// These points take the closed form or (series_friction_maxwell) the event-driven periodic
// state, both exact to rounding: 1e-9 and 1e-7 deg.
void check(const runtime::HarmonicPoint& p, std::complex<double> k_star) {
  CHECK(p.converged);
  CHECK(test::relative_error(p.measures.stiffness, std::abs(k_star)) < 1e-9);
  CHECK(std::abs(test::degrees(p.measures.phase - std::arg(k_star))) < 1e-7);
  MESSAGE("u0 " << p.amplitude << " mm, f " << p.frequency << " Hz: stiffness error " << test::relative_error(p.measures.stiffness, std::abs(k_star))
                << ", phase error " << std::abs(test::degrees(p.measures.phase - std::arg(k_star))) << " deg");
}
void check(const runtime::HarmonicPoint& p, const test::Measures& m, double stiffness_tolerance, double phase_tolerance_deg) {
  CHECK(p.converged);
  CHECK(test::relative_error(p.measures.stiffness, m.stiffness) < stiffness_tolerance);
  CHECK(std::abs(test::degrees(p.measures.phase - m.phase)) < phase_tolerance_deg);
  MESSAGE("u0 " << p.amplitude << " mm, f " << p.frequency << " Hz: stiffness error " << test::relative_error(p.measures.stiffness, m.stiffness)
                << ", phase error " << std::abs(test::degrees(p.measures.phase - m.phase)) << " deg");
}
double yeoh(double d10, double d20, double d30, double u) { return 2 * (d10 + 2 * d20 * u * u + 3 * d30 * u * u * u * u) * u; }

// The hydromount's uncapped complex stiffness (stdlib/hydromount_uncapped.rheo), default
// parameters: k_rubber 800 N/mm, k1 600 N/mm, b 0.04 N*s^2/mm, c 3 N*s/mm, k2 150 N/mm.
constexpr double k_rubber = 800, k1 = 600, inertance = 0.040, channel = 3, k2 = 150, cap = 60;
std::complex<double> hydromount_uncapped(double f) {
  const double w = 2 * std::numbers::pi * f;
  const std::complex<double> node{k2 - inertance * w * w, w * channel};
  return k_rubber + 1.0 / (1.0 / k1 + 1.0 / node);
}
// solver = automatic: the hydromounts' linear fluid column takes the closed form, capped by a
// slider the event-driven periodic state, both exact; IDA runs them in dae_protocols_test.
runtime::HarmonicOptions inerter_options() { return {}; }
runtime::HarmonicPoint hydro_point(const std::string& model, double u0, double f) {
  const auto network = test::network_from("import " + model + "\nmodel m { " + model + " h () }", "m");
  return runtime::simulate_harmonic_point(network, u0, f, inerter_options());
}
void check_within(const runtime::HarmonicPoint& p, std::complex<double> k_star, double stiffness_tolerance, double phase_tolerance_deg) {
  CHECK(p.converged);
  const double e_k = test::relative_error(p.measures.stiffness, std::abs(k_star));
  const double e_p = std::abs(test::degrees(p.measures.phase - std::arg(k_star)));
  CHECK(e_k < stiffness_tolerance);
  CHECK(e_p < phase_tolerance_deg);
  MESSAGE("u0 " << p.amplitude << " mm, f " << p.frequency << " Hz: stiffness error " << e_k << ", phase error " << e_p << " deg");
}
}  // namespace

TEST_CASE("stdlib kelvin_voigt: K* = k + i w c (B.41)") {
  const auto p = point("import kelvin_voigt\nmodel m { kelvin_voigt kv (k = 120 N/mm, c = 0.3 N*s/mm) }", "m", 0.5, 13.0);
  check(p, {120.0, 2 * std::numbers::pi * 13.0 * 0.3});
}

TEST_CASE("stdlib zener and maxwell3 (B.69, C.9) with their default parameters") {
  check(point("import zener\nmodel m { zener z () }", "m", 0.5, 9.0), 100.0 + test::maxwell(50, 0.01, 9.0));
  check(point("import maxwell3\nmodel m { maxwell3 g () }", "m", 0.5, 9.0),
        100.0 + test::maxwell(60, 1e-3, 9.0) + test::maxwell(40, 1e-2, 9.0) + test::maxwell(20, 0.1, 9.0));
}

TEST_CASE("stdlib frictional_zener (C.15) and viscoplastic (Fig. 2.5)") {
  // Slipping (u0 > us): F^ = (k_inf + kp us / u0) u0 (C.15), U = 4 kp us (u0 - us) (C.20), and
  // the phase asin(U / (pi F^ u0)) (C.12): 45 N, 15 N*mm, 20.71 deg.
  const double u0 = 0.3, kinf = 100, kp = 300, us = 0.05;
  const auto p = point("import frictional_zener\nmodel m { frictional_zener fz () }", "m", u0, 4.0);
  const double stiffness = kinf + kp * us / u0;
  CHECK(test::relative_error(p.measures.stiffness, stiffness) < 1e-9);
  CHECK(std::abs(test::degrees(p.measures.phase - std::asin(4 * kp * us * (u0 - us) / (std::numbers::pi * stiffness * u0 * u0)))) < 1e-7);
  // viscoplastic = spring + Maxwell + friction: at a frequency where the Maxwell arm is relaxed
  // (w tau = 6.3e-8) it is the frictional Zener of its spring and friction element (k_f 500 N/mm,
  // uy 50 um: fy = 25 N); the arm adds its loss pi u0^2 k_m w tau / (1 + (w tau)^2) = 8.9e-7 N*mm
  // to U and moves F^ by a relative (w tau)^2 / 2 at most, below the tolerance: 28.83 deg.
  const auto v = point("import viscoplastic\nmodel m { viscoplastic v (tau = 1 us) }", "m", u0, 0.01);
  const double k_v = 100.0 + 500.0 * 0.05 / u0, w_tau = 2 * std::numbers::pi * 0.01 * 1e-6;
  const double energy = 4 * 25.0 * (u0 - 0.05) + std::numbers::pi * u0 * u0 * 50.0 * w_tau / (1 + w_tau * w_tau);
  CHECK(test::relative_error(v.measures.stiffness, k_v) < 1e-9);
  CHECK(std::abs(test::degrees(v.measures.phase - std::asin(energy / (std::numbers::pi * k_v * u0 * u0)))) < 1e-7);
}

TEST_CASE("stdlib series_friction_maxwell: below the slip force it is a Zener model") {
  // Tiny amplitude: the slider never slips, the branch is the Maxwell arm (k 200, tau 10 ms).
  const auto p = point("import series_friction_maxwell\nmodel m { series_friction_maxwell s () }", "m", 0.01, 7.0);
  check(p, 100.0 + test::maxwell(200, 0.01, 7.0));
}

TEST_CASE("stdlib series_friction_maxwell slipping: a Jenkins element when the arm cannot relax, IDA agrees when it can") {
  // tau = 1e6 s: at 3 Hz the arm is a spring (relaxation ~ 1/(omega tau) = 5e-8), so the branch
  // is a friction element (k 200 N/mm, uy = fy / k = 0.1 mm): slipping at u0 = 0.5 mm, C.17-C.20.
  for (double u0 : {0.05, 0.5, 2.0}) {
    CAPTURE(u0);
    const auto p = point("import series_friction_maxwell\nmodel m { series_friction_maxwell s (tau = 1e6 s) }", "m", u0, 3.0);
    const test::Measures want = test::parallel_closed_form([](double u) { return 100 * u; }, {}, {{200, 0.1}}, u0, 3.0);
    CHECK(p.converged);
    CHECK(test::relative_error(p.measures.stiffness, want.stiffness) < 1e-6);
    CHECK(std::abs(test::degrees(p.measures.phase - want.phase)) < 1e-4);
  }
  // The default tau = 10 ms slips and relaxes at once (no closed form): the fixed-step kernels
  // and SUNDIALS IDA, two independent integrators, give the same point.
  const auto network = test::network_from("import series_friction_maxwell\nmodel m { series_friction_maxwell s () }", "m");
  runtime::HarmonicOptions ida;
  ida.solver = runtime::SolverChoice::sundials;
  // At 20 and 50 Hz (omega tau = 1.3, 3.1) the stuck arm's force amplitude, k u0 omega tau /
  // sqrt(1 + (omega tau)^2) = 78 and 95 N, would pass fy = 20 N.
  for (double f : {20.0, 50.0}) {
    CAPTURE(f);
    const auto fixed = runtime::simulate_harmonic_point(network, 0.5, f, {});
    const auto variable = runtime::simulate_harmonic_point(network, 0.5, f, ida);
    CHECK(fixed.converged);
    CHECK(variable.converged);
    CHECK(test::relative_error(fixed.measures.stiffness, variable.measures.stiffness) < 1e-5);  // seen: 4e-7
    CHECK(std::abs(test::degrees(fixed.measures.phase - variable.measures.phase)) < 1e-3);      // seen: 1.4e-5 deg
    // It does slip: the branch carries at most fy = 20 N above the spring's 100 u0.
    CHECK(fixed.measures.force_amplitude <= 100 * 0.5 + 20.0 * (1 + 1e-9));
    CHECK(fixed.measures.force_amplitude > 100 * 0.5 + 19.0);  // seen: 69.58 N at 20 Hz, 69.93 N at 50 Hz
  }
}

TEST_CASE("stdlib maxwell2: K* = k_inf + sum of two Maxwell arms (C.9)") {
  for (double f : {0.5, 9.0, 45.0}) {
    CAPTURE(f);
    check(point("import maxwell2\nmodel m { maxwell2 g () }", "m", 0.5, f), 100.0 + test::maxwell(60, 2e-3, f) + test::maxwell(30, 2e-2, f));
  }
  // Overrides reach the arms: the second arm moved to 1 ms.
  check(point("import maxwell2\nmodel m { maxwell2 g (tau2 = 1 ms) }", "m", 0.5, 30.0),
        100.0 + test::maxwell(60, 2e-3, 30.0) + test::maxwell(30, 1e-3, 30.0));
}

TEST_CASE("stdlib frictional_solid3: the generalized frictional solid (C.17-C.20) between and beyond its break points") {
  // Yield displacements 20, 50 and 150 um: all elastic at 10 um, then one, two and three slipping.
  const std::vector<test::Slip> f{{300, 0.020}, {200, 0.050}, {100, 0.150}};
  for (double u0 : {0.01, 0.03, 0.1, 0.5}) {
    CAPTURE(u0);
    double stiffness = 100, energy = 0;
    for (const auto& s : f) {
      stiffness += u0 > s.uy ? s.k * s.uy / u0 : s.k;         // C.17, C.18
      if (u0 > s.uy) energy += 4 * s.k * s.uy * (u0 - s.uy);  // C.20
    }
    const test::Measures want{stiffness, std::asin(energy / (std::numbers::pi * stiffness * u0 * u0))};  // C.12
    check(point("import frictional_solid3\nmodel m { frictional_solid3 s () }", "m", u0, 3.0), want, 1e-9, 1e-7);
    // ... and the hand-composed waveform agrees (the F^ search of the helpers below).
    const test::Measures wave = test::parallel_closed_form([](double u) { return 100 * u; }, {}, f, u0, 3.0);
    CHECK(test::relative_error(wave.stiffness, stiffness) < 1e-9);
  }
}

TEST_CASE("stdlib viscoplastic (Fig. 2.5) and nonlinear_viscoplastic (Fig. 2.6) against their exact steady state") {
  const std::vector<test::Arm> arm{{50, 5e-3}};
  const std::vector<test::Slip> slip{{500, 0.05}};
  for (double u0 : {0.03, 0.3, 2.5})
    for (double f : {2.0, 30.0}) {
      CAPTURE(u0);
      CAPTURE(f);
      check(point("import viscoplastic\nmodel m { viscoplastic v () }", "m", u0, f),
            test::parallel_closed_form([](double u) { return 100 * u; }, arm, slip, u0, f), 1e-9, 1e-7);
      const test::Measures nonlinear = test::parallel_closed_form([](double u) { return yeoh(50, -0.25, 0.01, u); }, arm, slip, u0, f);
      check(point("import nonlinear_viscoplastic\nmodel m { nonlinear_viscoplastic v () }", "m", u0, f), nonlinear, 1e-9, 1e-7);
      // The Yeoh spring matters at 2.5 mm: the linear-spring value would miss by percent.
      if (u0 > 2)
        CHECK(test::relative_error(test::parallel_closed_form([](double u) { return 100 * u; }, arm, slip, u0, f).stiffness, nonlinear.stiffness) >
              0.01);
    }
}

TEST_CASE("stdlib nonlinear_series_friction_maxwell (Fig. 9.1): a Yeoh spring beside a Maxwell arm while the slider sticks") {
  // fy raised to 2000 N: the branch force (at most k 2 u0 = 800 N) never reaches it, and the
  // response is the exact Yeoh + Maxwell waveform, non-linear at 2 mm.
  for (double f : {3.0, 20.0}) {
    CAPTURE(f);
    const auto p = point("import nonlinear_series_friction_maxwell\nmodel m { nonlinear_series_friction_maxwell s (fy = 2000 N) }", "m", 2.0, f);
    check(p, test::parallel_closed_form([](double u) { return yeoh(50, -0.25, 0.01, u); }, {{200, 0.01}}, {}, 2.0, f), 1e-9, 1e-7);
  }
  // Default fy = 20 N at 2 mm: the slider slips, the branch carries at most fy, so
  // F^ <= Y(u0) + fy, below the sticking response.
  const double u0 = 2.0, f = 20.0;
  const auto p = point("import nonlinear_series_friction_maxwell\nmodel m { nonlinear_series_friction_maxwell s () }", "m", u0, f);
  CHECK(p.converged);
  CHECK(p.measures.force_amplitude <= yeoh(50, -0.25, 0.01, u0) + 20.0 * (1 + 1e-9));
  CHECK(p.measures.force_amplitude > yeoh(50, -0.25, 0.01, u0));  // the branch does carry force
  const test::Measures stuck = test::parallel_closed_form([](double u) { return yeoh(50, -0.25, 0.01, u); }, {{200, 0.01}}, {}, u0, f);
  CHECK(p.measures.stiffness < stuck.stiffness);
}

TEST_CASE("stdlib hydromount_uncapped: K* = k_rubber + 1/(1/k1 + 1/(k2 - b w^2 + i w c)), through its resonance") {
  const double resonance = std::sqrt((k1 + k2) / inertance) / (2 * std::numbers::pi);  // 21.79 Hz
  for (double f : {1.0, 8.0, 15.0, resonance, 25.0, 40.0}) {
    CAPTURE(f);
    check_within(hydro_point("hydromount_uncapped", 0.5, f), hydromount_uncapped(f), 1e-9, 1e-7);
  }
  // The inerter is what makes the peak: its phase at the resonance is far above the low-frequency one.
  CHECK(std::arg(hydromount_uncapped(resonance)) > 5 * std::arg(hydromount_uncapped(1.0)));
}

TEST_CASE("stdlib hydromount: the uncapped closed form while the cap sticks, at most k_rubber u0 + fy once it slips") {
  const double resonance = std::sqrt((k1 + k2) / inertance) / (2 * std::numbers::pi);
  // 0.02 mm: the fluid force stays below 23 N (|K_fluid| <= 1107 N/mm), far from fy = 60 N,
  // even in the start-up transient.
  for (double f : {5.0, resonance, 30.0}) {
    CAPTURE(f);
    check_within(hydro_point("hydromount", 0.02, f), hydromount_uncapped(f), 1e-9, 1e-7);
  }
  // 1 mm: the uncapped fluid force would reach 1000 N; capped, the fluid carries at most fy.
  for (double f : {resonance, 25.0}) {
    CAPTURE(f);
    const double u0 = 1.0;
    const auto p = hydro_point("hydromount", u0, f);
    CHECK(p.converged);
    CHECK(p.measures.force_amplitude <= k_rubber * u0 + cap * (1 + 1e-6));
    CHECK(p.measures.force_amplitude >= k_rubber * u0 - cap * (1 + 1e-6));
    CHECK(p.measures.phase < std::arg(hydromount_uncapped(f)));
    MESSAGE("capped at 1 mm, " << f << " Hz: F^ = " << p.measures.force_amplitude << " N (bound " << k_rubber * u0 + cap << "), phase "
                               << test::degrees(p.measures.phase) << " deg vs uncapped " << test::degrees(std::arg(hydromount_uncapped(f))));
  }
}

TEST_CASE("stdlib fractional_zener: K* = k_inf + 1/(1/k1 + 1/(k_sp (i w tau)^alpha)) across the springpot's band") {
  for (double f : {0.02, 1.0, 30.0, 800.0}) {
    const std::complex<double> springpot = 50.0 * std::pow(std::complex<double>{0.0, 2 * std::numbers::pi * f * 0.01}, 0.3);
    const auto p = point("import fractional_zener\nmodel m { fractional_zener z () }", "m", 0.5, f);
    CHECK(p.cycles == 0);  // closed form: the springpot's Maxwell chain is linear
    check_within(p, 100.0 + 1.0 / (1.0 / 200.0 + 1.0 / springpot), 5e-4, 0.02);
  }
}

TEST_CASE("every stdlib model is covered above") {
  // A new stdlib model must get a test here before this list is extended.
  auto names = lang::stdlib_names();
  std::sort(names.begin(), names.end());
  CHECK(names == std::vector<std::string>{"fractional_zener", "frictional_solid3", "frictional_zener", "hydromount", "hydromount_uncapped",
                                          "kelvin_voigt", "maxwell2", "maxwell3", "nonlinear_series_friction_maxwell", "nonlinear_viscoplastic",
                                          "series_friction_maxwell", "viscoplastic", "zener"});
}

}  // namespace stdlib_models_test
