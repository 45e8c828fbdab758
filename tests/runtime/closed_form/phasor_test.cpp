// Second path: the phasor composition of linear networks against closed forms and against the
// time-stepping harmonic protocol on nested networks.
#include "runtime/closed_form/phasor.hpp"

#include "runtime/protocols/harmonic.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

namespace phasor_test {

using namespace rheo;

TEST_CASE("phasor composition: series spring + Kelvin-Voigt block (standard linear solid)") {
  const auto model = test::model_from("model z { series { spring a (k = 300) parallel { spring b (k = 100) dashpot c (c = 2) } } }", "z");
  std::vector<double> values;
  for (const auto& p : model.parameters) values.push_back(p.value);
  const double w = 2 * std::numbers::pi * 5.0;
  const std::complex<double> kv{100.0, 2.0 * w};
  const auto k = runtime::complex_stiffness(model, values, 5.0);
  REQUIRE(k);
  CHECK(std::abs(*k - 300.0 * kv / (300.0 + kv)) < 1e-12 * std::abs(*k));
}

TEST_CASE("phasor composition rejects non-linear networks") {
  const auto model = test::model_from("model f { spring a (k = 1) friction b (k = 2, fy = 1) }", "f");
  CHECK_FALSE(runtime::complex_stiffness(model, {1.0, 2.0, 1.0}, 1.0));
}

TEST_CASE("time stepping agrees with the phasor path on nested linear networks") {
  // Maxwell pairs written by hand (series spring + dashpot) are fused to exact updates;
  // a dashpot behind an internal node is integrated implicitly: first order in the step,
  // so its tolerance is looser and its error must halve with the step (time stepping forced:
  // the default would take the closed form, exact, and the halving would test nothing).
  const auto exact = test::model_from(R"(
    model m {
      spring e (k = 90)
      series a { spring s (k = 40) dashpot d (c = 0.8) }
      parallel p { maxwell m (k = 25, tau = 5 ms) series { spring s2 (k = 10) dashpot d2 (c = 0.05) } }
    })",
                                      "m");
  const auto implicit = test::model_from("model z { series { spring a (k = 300) parallel { spring b (k = 100) dashpot c (c = 2) } } }", "z");
  for (double f : {2.0, 17.0}) {
    std::vector<double> values;
    for (const auto& p : exact.parameters) values.push_back(p.value);
    const auto k = *runtime::complex_stiffness(exact, values, f);
    runtime::HarmonicOptions stepping;
    stepping.steady_state = runtime::SteadyState::time_stepping;
    const auto point = runtime::simulate_harmonic_point(runtime::Network::compile(exact), 0.4, f, stepping);
    CHECK(point.converged);
    // Second order at N = 2048 (harmonic_test.cpp): 5e-6 and 3e-4 deg; observed 5e-7, 9e-6 deg.
    CHECK(test::relative_error(point.measures.stiffness, std::abs(k)) < 5e-6);
    CHECK(std::abs(test::degrees(point.measures.phase - std::arg(k))) < 3e-4);

    std::vector<double> v2;
    for (const auto& p : implicit.parameters) v2.push_back(p.value);
    const auto k2 = *runtime::complex_stiffness(implicit, v2, f);
    runtime::HarmonicOptions coarse;
    coarse.steady_state = runtime::SteadyState::time_stepping;  // auto would take the closed form, exact
    runtime::HarmonicOptions fine = coarse;
    fine.steps_per_cycle = 2 * coarse.steps_per_cycle;
    const auto net = runtime::Network::compile(implicit);
    const double e1 = test::relative_error(runtime::simulate_harmonic_point(net, 0.4, f, coarse).measures.stiffness, std::abs(k2));
    const double e2 = test::relative_error(runtime::simulate_harmonic_point(net, 0.4, f, fine).measures.stiffness, std::abs(k2));
    MESSAGE("f = " << f << " Hz: nested exact updates " << test::relative_error(point.measures.stiffness, std::abs(k)) << ", "
                   << std::abs(test::degrees(point.measures.phase - std::arg(k))) << " deg; implicit dashpot " << e1 << " -> " << e2);
    CHECK(e1 < 1e-3);                                                // observed 2.7e-4 and 4.9e-5
    CHECK(e2 / e1 == doctest::Approx(0.5).epsilon(0.1).scale(0.0));  // first order
  }
}

TEST_CASE("phasor composition: an inerter is K* = -b w^2, in parallel and in series") {
  auto k_star = [](const char* source, double f) {
    const auto model = test::model_from(source, "i");
    std::vector<double> values;
    for (const auto& p : model.parameters) values.push_back(p.value);
    return runtime::complex_stiffness(model, values, f);
  };
  const double w = 2 * std::numbers::pi * 30.0, k = 300, b = 2e-3;
  const auto parallel = k_star("model i { spring k (k = 300) inerter m (b = 2 kg) }", 30.0);
  REQUIRE(parallel);
  CHECK(std::abs(*parallel - std::complex<double>{k - b * w * w, 0.0}) < 1e-12 * k);
  const auto series = k_star("model i { series { spring k (k = 300) inerter m (b = 2 kg) } }", 30.0);
  REQUIRE(series);
  CHECK(std::abs(*series - k * (-b * w * w) / (k - b * w * w)) < 1e-12 * k);
  CHECK_FALSE(k_star("model i { quadratic_dashpot q (cq = 1 N*s^2/mm^2) }", 30.0));
  CHECK_FALSE(k_star("model i { series { gap g (width = 1 mm) spring s (k = 1) } }", 30.0));
  CHECK_FALSE(k_star("model i { bouc_wen w (k = 1, n = 1, fy = 1) }", 30.0));
}

}  // namespace phasor_test
