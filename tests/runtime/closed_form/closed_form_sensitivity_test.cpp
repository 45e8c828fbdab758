// closed_form_sensitivity: the analytic derivatives of F^, K'_1 and K''_1, chained to a model
// parameter through the coefficients it moves, against central differences of the closed form
// itself (an independent path: the maximum is searched afresh at each moved value), for every
// root element kind, friction elements elastic and slipping, Maxwell elements on both sides of
// w tau = 1, and measure_derivative against differences of measures_from.
#include "runtime/closed_form/closed_form_sensitivity.hpp"

#include "runtime/closed_form/periodic_closed_form.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

namespace closed_form_sensitivity_test {

using namespace rheo;

namespace {

// Every kind of root element; the expression 2 * kd shares a parameter between two coefficients.
const char* const kEveryRootKind = R"(model m {
  param kd = 40 N/mm
  spring s (k = 120)
  dashpot d (c = 0.3)
  yeoh y (D10 = 150, D20 = -2, D30 = 0.4)
  maxwell x1 (k = 2 * kd, tau = 4 ms)
  maxwell x2 (k = kd, tau = 0.2 s)
  friction f1 (k = 300, uy = 30 um)
  friction f2 (k = 90, uy = 0.4 mm)
  slider sl (fy = 3 N)
  springpot sp (k = 30, alpha = 0.3, tau = 10 ms)
})";

struct Summary {
  double force_amplitude, storage, loss;
};

Summary summary(const runtime::Network& network, double u0, double f) {
  const runtime::CycleMeasures m = runtime::closed_form_harmonic_point(network, u0, f, runtime::HarmonicDefinition::first_harmonic).measures;
  return {m.force_amplitude, m.storage, m.loss};
}

}  // namespace

TEST_CASE("F^, K'_1 and K''_1 derivatives match central differences of the closed form for every parameter") {
  const runtime::Network network = test::network_from(kEveryRootKind, "m");
  REQUIRE(runtime::has_coefficient_sensitivities(network));
  const std::vector<double> base = runtime::coefficient_vector(network.coefficients());
  int compared = 0;
  // 0.02 mm: f1 elastic (uy 30 um), f2 elastic; 0.1 mm: f1 slipping; 1.5 mm: both slipping.
  for (double u0 : {0.02, 0.1, 1.5})
    for (double f : {0.3, 5.0, 60.0}) {
      const runtime::HarmonicSensitivity s = runtime::harmonic_sensitivity(network, u0, f, runtime::HarmonicDefinition::first_harmonic);
      REQUIRE(s.force_amplitude.size() == base.size());
      for (std::size_t i = 0; i < network.parameters().size(); ++i) {
        std::vector<double> values = network.parameters();
        const double p = values[i], h = 1e-6 * std::abs(p);
        values[i] = p + h;
        const runtime::Network up = network.with_parameters(values);
        values[i] = p - h;
        const runtime::Network down = network.with_parameters(values);
        // The chain through the coefficients: dm/dp = sum_k dm/dC_k dC_k/dp (exact for these affine maps).
        const std::vector<double> c_up = runtime::coefficient_vector(up.coefficients()), c_down = runtime::coefficient_vector(down.coefficients());
        Summary analytic{0.0, 0.0, 0.0};
        for (std::size_t k = 0; k < base.size(); ++k) {
          const double dc = (c_up[k] - c_down[k]) / (2.0 * h);
          analytic.force_amplitude += s.force_amplitude[k] * dc;
          analytic.storage += s.storage[k] * dc;
          analytic.loss += s.loss[k] * dc;
        }
        const Summary a = summary(up, u0, f), b = summary(down, u0, f);
        const Summary difference{(a.force_amplitude - b.force_amplitude) / (2.0 * h), (a.storage - b.storage) / (2.0 * h),
                                 (a.loss - b.loss) / (2.0 * h)};
        // Scale: the change of each measure for a 100 % change of p; differences good to ~1e-8 of it.
        const Summary at = summary(network, u0, f);
        INFO("u0 = " << u0 << " mm, f = " << f << " Hz, parameter " << network.model().parameters[i].path);
        CHECK(std::abs(analytic.force_amplitude - difference.force_amplitude) * p <= 1e-6 * at.force_amplitude);
        CHECK(std::abs(analytic.storage - difference.storage) * p <= 1e-6 * std::hypot(at.storage, at.loss));
        CHECK(std::abs(analytic.loss - difference.loss) * p <= 1e-6 * std::hypot(at.storage, at.loss));
        ++compared;
      }
    }
  CHECK(compared == 9 * static_cast<int>(network.parameters().size()));
}

TEST_CASE("measure derivatives follow measures_from under both definitions") {
  const runtime::Network network = test::network_from(kEveryRootKind, "m");
  for (runtime::HarmonicDefinition definition : {runtime::HarmonicDefinition::thesis, runtime::HarmonicDefinition::first_harmonic}) {
    const runtime::HarmonicSensitivity s = runtime::harmonic_sensitivity(network, 0.4, 7.0, definition);
    const runtime::CycleMeasures& m = s.point.measures;
    const double storage1 = definition == runtime::HarmonicDefinition::first_harmonic ? m.storage : 0.0;  // thesis: K'_1 only by its sign
    // One direction moving all three: (dF^, dK', dK'') = (2, -3, 1.5) N/mm per unit.
    const double h = 1e-7, df = 2.0, ds = -3.0, dl = 1.5;
    const double k1 = definition == runtime::HarmonicDefinition::first_harmonic ? storage1 : 1.0;  // thesis: K'_1 > 0 keeps the phase below 90 deg
    const double k2 = m.energy / (std::numbers::pi * 0.4 * 0.4);
    auto at = [&](double t) { return runtime::measures_from(m.force_amplitude + t * df, k1 + t * ds, k2 + t * dl, 0.4, definition); };
    const runtime::CycleMeasures plus = at(h), minus = at(-h);
    const runtime::MeasureDerivative d = runtime::measure_derivative(s, definition, df, ds, dl);
    INFO("definition " << static_cast<int>(definition));
    CHECK(d.stiffness == doctest::Approx((plus.stiffness - minus.stiffness) / (2.0 * h)).epsilon(1e-6));
    // sin and cos are of order 1: their central differences at h = 1e-7 are good to ~1e-16 / h =
    // 1e-9 absolute (measured 2e-10), not relative to derivatives of 2e-4 (absolute tolerance 1e-8).
    CHECK(d.sine == doctest::Approx((std::sin(plus.phase) - std::sin(minus.phase)) / (2.0 * h)).epsilon(1e-8).scale(1.0));
    CHECK(d.cosine == doctest::Approx((std::cos(plus.phase) - std::cos(minus.phase)) / (2.0 * h)).epsilon(1e-8).scale(1.0));
  }
}

}  // namespace closed_form_sensitivity_test
