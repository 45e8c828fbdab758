// The thesis approximation (5.12-5.21) against the phasor path (linear networks: exact), hand
// values of (5.16)-(5.19) and the exact steady state (springs + friction: exact), its deviation
// from the exact steady state on specimen D, and the Table 5.1 correction (5.2-5.4).
#include "runtime/fit/thesis_approximation.hpp"
#include "runtime/protocols/harmonic.hpp"

#include "runtime/closed_form/phasor.hpp"
#include "support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace thesis_approximation_test {

using namespace rheo;
using std::numbers::pi;
using test::relative_error;

namespace {

std::vector<double> values_of(const lang::CheckedModel& model) {
  std::vector<double> v;
  for (const auto& p : model.parameters) v.push_back(p.value);
  return v;
}

runtime::Network specimen_d() {
  const auto program = lang::load_program(std::string(RHEO_EXAMPLES_DIR) + "/specimen_d.rheo");
  return runtime::Network::compile(*program.find_model("specimen_d"));
}

std::string rejection(const std::string& source, const std::string& name) {
  return runtime::approximation_misfit(test::network_from(source, name));
}

}  // namespace

TEST_CASE("linear network: the approximation is |K*| and sin(arg K*) of the phasor path") {
  // Spring, three Maxwell elements of specimen C (Table D.3) and a hand-written spring + dashpot pair.
  const auto model = test::model_from(R"(
    model gm {
      spring  e  (k = 490.629)
      maxwell m1 (k = 111.5544, tau = 0.0013 s)
      maxwell m2 (k = 309.3259, tau = 0.5845 s)
      maxwell m3 (k = 143.1166, tau = 0.0157 s)
      series pair { spring s (k = 40) dashpot d (c = 0.8) }
    })",
                                      "gm");
  const auto net = runtime::Network::compile(model);
  const std::vector<double> frequencies{0.01, 0.1, 1.0, 3.0, 17.0, 41.0, 300.0};
  const std::vector<double> amplitudes(frequencies.size(), 0.7);
  const auto points = runtime::approximate_harmonic(net, amplitudes, frequencies);
  REQUIRE(points.size() == frequencies.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto k = *runtime::complex_stiffness(model, values_of(model), frequencies[i]);
    const auto& m = points[i].measures;
    CAPTURE(frequencies[i]);
    CHECK(points[i].converged);
    CHECK(points[i].amplitude == 0.7);
    CHECK(points[i].frequency == frequencies[i]);
    CHECK(relative_error(m.stiffness, std::abs(k)) < 1e-12);
    CHECK(std::abs(m.damping - std::sin(std::arg(k))) < 1e-12);
    CHECK(std::abs(m.phase - std::arg(k)) < 1e-12);
    CHECK(std::abs(m.storage - k.real()) < 1e-12 * std::abs(k));
    CHECK(std::abs(m.loss - k.imag()) < 1e-12 * std::abs(k));
    CHECK(relative_error(m.force_amplitude, std::abs(k) * 0.7) < 1e-12);
    CHECK(relative_error(m.energy, pi * 0.49 * k.imag()) < 1e-12);  // U = pi u0^2 K''
  }
}

TEST_CASE("a yeoh spring enters with K_e = 2 D10 (5.34, 5.35)") {
  const auto yeoh = test::network_from("model y { yeoh r (D10 = 50, D20 = -3, D30 = 0.2) maxwell m (k = 30, tau = 5 ms) }", "y");
  const auto spring = test::network_from("model s { spring r (k = 100) maxwell m (k = 30, tau = 5 ms) }", "s");
  const auto a = runtime::approximate_harmonic(yeoh, {0.5, 2.0}, {3.0, 30.0});
  const auto b = runtime::approximate_harmonic(spring, {0.5, 2.0}, {3.0, 30.0});
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(a[i].measures.stiffness == doctest::Approx(b[i].measures.stiffness).epsilon(1e-15));
    CHECK(a[i].measures.damping == doctest::Approx(b[i].measures.damping).epsilon(1e-15).scale(0.0));
  }
}

TEST_CASE("spring + friction elements: hand values of (5.16)-(5.21)") {
  // K_e = 120; f1: K_p = 300, u_s = 0.05 (F_y = 15); f2: K_p = 100, u_s = 0.2 (F_y = 20).
  const auto net = test::network_from("model f { spring e (k = 120) friction f1 (k = 300, uy = 50 um) friction f2 (k = 100, uy = 0.2 mm) }", "f");
  const auto p = runtime::approximate_harmonic(net, {0.02, 0.1, 0.3}, {5.0, 5.0, 5.0});
  // u0 = 0.02: neither slips: K = 120 + 300 + 100, no dissipation.
  CHECK(p[0].measures.stiffness == doctest::Approx(520.0).epsilon(1e-14));
  CHECK(p[0].measures.damping == 0.0);
  // u0 = 0.1: f1 slips (K^p1 = 15/0.1 = 150, U1 = 4*15*0.05 = 3), f2 elastic (K^p2 = 100).
  // K = 120 + 250 = 370; F^_p = 0.1 * 250 = 25; d_p = 3/(pi 0.1 25); d = 250 d_p / 370 = 3/(pi 0.01 370).
  // (The printed 5.19 would divide by pi 0.1 (15 + 20) instead: d_p = 3/(3.5 pi), 29 % lower.)
  CHECK(p[1].measures.stiffness == doctest::Approx(370.0).epsilon(1e-14));
  CHECK(p[1].measures.damping == doctest::Approx(3.0 / (pi * 0.01 * 370.0)).epsilon(1e-14).scale(0.0));
  // u0 = 0.3: both slip, K^p = (15 + 20)/0.3, U = 4*15*0.25 + 4*20*0.1 = 23, d_p = 23/(pi 0.3 35) (= printed 5.19).
  const double kp = 35.0 / 0.3, dp = 23.0 / (pi * 0.3 * 35.0);
  CHECK(p[2].measures.stiffness == doctest::Approx(120.0 + kp).epsilon(1e-14));
  CHECK(p[2].measures.damping == doctest::Approx(kp * dp / (120.0 + kp)).epsilon(1e-14).scale(0.0));
  CHECK(p[2].measures.phase == doctest::Approx(std::asin(kp * dp / (120.0 + kp))).epsilon(1e-14).scale(0.0));
}

TEST_CASE("spring + friction elements: the approximation equals the exact steady state (C.15, C.17-C.18, C.12)") {
  const auto net = test::network_from(R"(
    model gfs {
      spring   e  (k = 80)
      friction f1 (k = 1016.6, uy = 101.58 um)
      friction f2 (k = 301.04, uy = 42.256 um)
      friction f3 (k = 25.516, uy = 12.695 um)
    })",
                                      "gfs");
  const std::vector<double> amplitudes{0.01, 0.03, 0.07, 0.2, 1.5};
  const auto approx = runtime::approximate_harmonic(net, amplitudes, std::vector<double>(amplitudes.size(), 11.0));
  for (std::size_t i = 0; i < amplitudes.size(); ++i) {
    const auto exact = runtime::simulate_harmonic_point(net, amplitudes[i], 11.0, {});
    CAPTURE(amplitudes[i]);
    CHECK(relative_error(approx[i].measures.stiffness, exact.measures.stiffness) < 1e-6);
    CHECK(std::abs(approx[i].measures.damping - exact.measures.damping) < 1e-6);
  }
}

TEST_CASE("networks outside Figs. 5.1/5.3 are rejected with the element and the way out") {
  const std::string dashpot = rejection("model kv { spring s (k = 1) dashpot d (c = 2) }", "kv");
  CHECK(dashpot.find("dashpot 'd'") != std::string::npos);
  CHECK(dashpot.find("method = exact") != std::string::npos);
  CHECK(dashpot.find("spring") != std::string::npos);
  const std::string slider = rejection("model s { spring e (k = 1) slider g (fy = 2) }", "s");
  CHECK(slider.find("slider 'g'") != std::string::npos);
  const std::string nested = rejection("model n { spring e (k = 1) series b { spring s (k = 5) friction f (k = 2, fy = 1) } }", "n");
  CHECK(nested.find("'b.s'") != std::string::npos);
  CHECK(nested.find("nested") != std::string::npos);
  CHECK(rejection("model m { spring e (k = 1) series b { spring s (k = 5) dashpot d (c = 1) } }", "m").empty());
  // A misfit is the caller's to report (fit() makes it a UsageError); past it, a broken precondition.
  CHECK_THROWS_AS(runtime::approximate_harmonic(test::network_from("model kv { spring s (k = 1) dashpot d (c = 2) }", "kv"), {1.0}, {1.0}),
                  std::logic_error);
  const auto net = test::network_from("model z { spring e (k = 1) }", "z");
  CHECK_THROWS_AS(runtime::approximate_harmonic(net, {1.0, 2.0}, {1.0}), std::logic_error);
  CHECK_THROWS_AS(runtime::approximate_harmonic(net, {0.0}, {1.0}), std::logic_error);
}

TEST_CASE("specimen D: the approximation deviates from the exact steady state by a bounded amount, 5.2-5.4 calibrate it") {
  // The deviation has three sources: the linearised yeoh spring (K_e = 2 D10 ignores D20, D30:
  // F^ of the spring alone is 4.9 % low at 3 mm), the scalar sum (5.20) of viscous and frictional
  // stiffness that peak at different times (cos delta = 1, 5.6), and the weighted damping (5.21).
  const auto net = specimen_d();
  std::vector<double> amplitudes, frequencies;
  for (double u0 : {0.2, 0.5, 0.8, 1.0, 1.5, 2.0, 3.0})
    for (double f = 1.0; f <= 51.0; f += 2.0) {
      amplitudes.push_back(u0);
      frequencies.push_back(f);
    }
  auto approx = runtime::approximate_harmonic(net, amplitudes, frequencies);
  std::vector<runtime::HarmonicPoint> exact;
  for (std::size_t i = 0; i < amplitudes.size(); ++i) exact.push_back(runtime::simulate_harmonic_point(net, amplitudes[i], frequencies[i], {}));
  double worst_k = 0.0, worst_phase = 0.0, worst_d = 0.0, mean_k = 0.0;
  std::size_t worst_k_at = 0, worst_phase_at = 0;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    REQUIRE(exact[i].converged);
    const double ek = approx[i].measures.stiffness / exact[i].measures.stiffness - 1.0;
    const double ep = test::degrees(approx[i].measures.phase - exact[i].measures.phase);
    const double ed = approx[i].measures.damping / exact[i].measures.damping - 1.0;
    mean_k += ek / static_cast<double>(exact.size());
    if (std::abs(ek) > std::abs(worst_k)) {
      worst_k = ek;
      worst_k_at = i;
    }
    if (std::abs(ep) > std::abs(worst_phase)) {
      worst_phase = ep;
      worst_phase_at = i;
    }
    worst_d = std::max(worst_d, std::abs(ed));
  }
  MESSAGE(
      fmt::format("specimen D, approximation - exact: stiffness worst {:+.3f} % at ({} mm, {} Hz), mean {:+.3f} %; "
                  "phase worst {:+.3f} deg at ({} mm, {} Hz); damping worst |rel| {:.3f} %",
                  100 * worst_k, amplitudes[worst_k_at], frequencies[worst_k_at], 100 * mean_k, worst_phase, amplitudes[worst_phase_at],
                  frequencies[worst_phase_at], 100 * worst_d));
  // Observed: stiffness +4.81 % at (3 mm, 1 Hz), mean +1.62 %; phase -0.263 deg at (3 mm, 31 Hz);
  // damping 4.6 %. The stiffness error is the linearised yeoh spring: at 3 mm its F^ is
  // 2223 N, not 2 D10 u0 = 2337 N, i.e. 38 N/mm on an exact K of 784 N/mm. Bounds: about 1.25x the observed
  // worst, and a floor that fails if the approximation were (wrongly) the exact path.
  CHECK(std::abs(worst_k) < 0.06);
  CHECK(std::abs(worst_k) > 0.03);
  CHECK(std::abs(worst_phase) < 0.35);
  CHECK(std::abs(worst_phase) > 0.1);
  CHECK(worst_d < 0.06);

  const auto correction = runtime::thesis_correction(approx, exact);
  runtime::apply_correction(correction, approx);
  for (std::size_t i = 0; i < exact.size(); ++i) {
    CHECK(relative_error(approx[i].measures.stiffness, exact[i].measures.stiffness) < 1e-15);
    CHECK(relative_error(approx[i].measures.damping, exact[i].measures.damping) < 1e-15);
    CHECK(std::abs(approx[i].measures.phase - exact[i].measures.phase) < 1e-14);
  }
}

TEST_CASE("the approximation on two threads gives the one thread's points, bit for bit") {
  const auto net = specimen_d();
  std::vector<double> amplitudes, frequencies;
  for (double u0 : {0.2, 1.0, 3.0})
    for (double f = 1.0; f <= 51.0; f += 5.0) amplitudes.push_back(u0), frequencies.push_back(f);
  const auto one = runtime::approximate_harmonic(net, amplitudes, frequencies, 1);
  const auto two = runtime::approximate_harmonic(net, amplitudes, frequencies, 2);
  REQUIRE(two.size() == one.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    CHECK(two[i].amplitude == one[i].amplitude);
    CHECK(two[i].frequency == one[i].frequency);
    CHECK(two[i].measures.stiffness == one[i].measures.stiffness);
    CHECK(two[i].measures.phase == one[i].measures.phase);
  }
}

TEST_CASE("the correction refuses points that do not match") {
  const auto net = test::network_from("model z { spring e (k = 100) friction f (k = 50, fy = 1) }", "z");
  const auto a = runtime::approximate_harmonic(net, {0.01, 0.1}, {1.0, 1.0});
  const auto b = runtime::approximate_harmonic(net, {0.01, 0.2}, {1.0, 1.0});
  CHECK_THROWS_AS(runtime::thesis_correction(a, b), std::logic_error);
  CHECK_THROWS_AS(runtime::thesis_correction(a, {a[0]}), std::logic_error);
  const auto c = runtime::thesis_correction(a, a);
  CHECK(c.stiffness == std::vector<double>{1.0, 1.0});
  CHECK(c.damping == std::vector<double>{1.0, 1.0});  // d = 0 at 0.01 mm (elastic): corr_d = 1 by convention
  auto copy = a;
  CHECK_THROWS_AS(runtime::apply_correction({{1.0}, {1.0}}, copy), std::logic_error);
}

}  // namespace thesis_approximation_test
