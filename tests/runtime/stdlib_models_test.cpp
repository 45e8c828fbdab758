// Every standard-library model simulates as its header equation says: the linear ones against
// the phasor composition of their closed forms, the frictional ones against C.15.
#include "lang/stdlib.hpp"
#include "runtime/harmonic.hpp"
#include "runtime/phasor.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <complex>

using namespace rheo;

namespace {
runtime::HarmonicPoint point(const std::string& source, const std::string& model, double u0, double f) {
  return runtime::simulate_harmonic_point(test::network_from(source, model), u0, f, {});
}
void check(const runtime::HarmonicPoint& p, std::complex<double> k_star) {
  CHECK(p.converged);
  CHECK(test::relative_error(p.measures.stiffness, std::abs(k_star)) < 1e-5);
  CHECK(std::abs(test::degrees(p.measures.phase - std::arg(k_star))) < 1e-3);
}
std::complex<double> maxwell(double k, double tau, double f) {
  const std::complex<double> iwt{0.0, 2 * std::numbers::pi * f * tau};
  return k * iwt / (1.0 + iwt);
}
}  // namespace

TEST_CASE("stdlib kelvin_voigt: K* = k + i w c (B.41)") {
  const auto p = point("import kelvin_voigt\nmodel m { kelvin_voigt kv (k = 120 N/mm, c = 0.3 N*s/mm) }", "m", 0.5, 13.0);
  check(p, {120.0, 2 * std::numbers::pi * 13.0 * 0.3});
}

TEST_CASE("stdlib zener and maxwell3 (B.69, C.9) with their default parameters") {
  check(point("import zener\nmodel m { zener z () }", "m", 0.5, 9.0), 100.0 + maxwell(50, 0.01, 9.0));
  check(point("import maxwell3\nmodel m { maxwell3 g () }", "m", 0.5, 9.0),
        100.0 + maxwell(60, 1e-3, 9.0) + maxwell(40, 1e-2, 9.0) + maxwell(20, 0.1, 9.0));
}

TEST_CASE("stdlib frictional_zener (C.15) and viscoplastic (Fig. 2.5)") {
  const double u0 = 0.3, kinf = 100, kp = 300, us = 0.05;
  const auto p = point("import frictional_zener\nmodel m { frictional_zener fz () }", "m", u0, 4.0);
  CHECK(test::relative_error(p.measures.stiffness, kinf + kp * us / u0) < 1e-5);
  // viscoplastic = spring + Maxwell + friction: at a frequency where the Maxwell arm is relaxed
  // (w tau << 1) it tends to the frictional Zener of its spring and friction element.
  const auto v = point("import viscoplastic\nmodel m { viscoplastic v (tau = 1 us) }", "m", u0, 0.01);
  CHECK(test::relative_error(v.measures.stiffness, 100.0 + 500.0 * 0.05 / u0) < 1e-5);
}

TEST_CASE("stdlib series_friction_maxwell: below the slip force it is a Zener model") {
  // Tiny amplitude: the slider never slips, the branch is the Maxwell arm (k 200, tau 10 ms).
  const auto p = point("import series_friction_maxwell\nmodel m { series_friction_maxwell s () }", "m", 0.01, 7.0);
  check(p, 100.0 + maxwell(200, 0.01, 7.0));
}

TEST_CASE("every stdlib model is covered above") {
  // A new stdlib model must get a test here before this list is extended.
  auto names = lang::stdlib_names();
  std::sort(names.begin(), names.end());
  CHECK(names == std::vector<std::string>{"frictional_zener", "kelvin_voigt", "maxwell3", "series_friction_maxwell",
                                          "viscoplastic", "zener"});
}
