// The springpot's Maxwell chain against the fractional element it approximates:
// K*(w) = k (i w tau)^alpha in the frequency domain and G(t) = k (t/tau)^-alpha / Gamma(1 - alpha)
// in the time domain.
#include "runtime/network/springpot.hpp"

#include "runtime/protocols/run_history.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/closed_form/periodic_closed_form.hpp"
#include "runtime/closed_form/phasor.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

namespace springpot_test {

using namespace rheo;
using Complex = std::complex<double>;

namespace {

struct Chain {
  std::vector<double> k, c;
  explicit Chain(const runtime::SpringpotParameters& p) {
    const auto n = static_cast<std::size_t>(runtime::springpot_mode_count(p.f_low, p.f_high));
    k.resize(n);
    c.resize(n);
    runtime::springpot_modes(p, k, c);
  }
  Complex stiffness(double frequency) const {
    const double w = 2.0 * std::numbers::pi * frequency;
    Complex sum{0.0, 0.0};
    for (std::size_t j = 0; j < k.size(); ++j) {
      const Complex iwl{0.0, w * c[j] / k[j]};
      sum += k[j] * iwl / (1.0 + iwl);
    }
    return sum;
  }
  double relaxation(double t) const {
    double sum = 0.0;
    for (std::size_t j = 0; j < k.size(); ++j) sum += k[j] * std::exp(-t * k[j] / c[j]);
    return sum;
  }
};

Complex exact_stiffness(const runtime::SpringpotParameters& p, double frequency) {
  return p.k * std::pow(Complex{0.0, 2.0 * std::numbers::pi * frequency * p.tau}, p.alpha);
}

// Log-spaced points over [lo, hi], ends included.
std::vector<double> log_points(double lo, double hi, int count) {
  std::vector<double> out;
  for (int i = 0; i < count; ++i) out.push_back(lo * std::pow(hi / lo, static_cast<double>(i) / (count - 1)));
  return out;
}

}  // namespace

TEST_CASE("mode count: 4 per decade over the band widened by 1.5 decades each side, plus the two tails") {
  CHECK(runtime::springpot_mode_count(0.01, 1000.0) == 4 * 8 + 2);
  CHECK(runtime::springpot_mode_count(1.0, 100.0) == 4 * 5 + 2);
  CHECK(runtime::springpot_mode_count(1.0, 1.5) == 15);  // ceil(4 * (3 + log10 1.5)) + 2
}

TEST_CASE("K* of the chain is k (i w tau)^alpha within 5e-4 and 0.02 deg over the band") {
  for (double alpha : {0.02, 0.1, 0.3, 0.5, 0.7, 0.9, 0.98})
    for (const auto& band : {std::pair{0.01, 1000.0}, std::pair{1.0, 100.0}, std::pair{20.0, 20000.0}}) {
      const double f_low = band.first, f_high = band.second;  // not a structured binding: Clang 14 cannot capture one
      const runtime::SpringpotParameters p{120.0, alpha, 3e-3, f_low, f_high};
      const Chain chain(p);
      double worst_magnitude = 0.0, worst_phase = 0.0;
      for (double f : log_points(f_low, f_high, 61)) {
        const Complex ratio = chain.stiffness(f) / exact_stiffness(p, f);
        worst_magnitude = std::max(worst_magnitude, std::abs(std::abs(ratio) - 1.0));
        worst_phase = std::max(worst_phase, std::abs(test::degrees(std::arg(ratio))));
      }
      CAPTURE(alpha);
      CAPTURE(f_low);
      CHECK(worst_magnitude < 5e-4);
      CHECK(worst_phase < 0.02);
    }
}

TEST_CASE("the chain relaxes like k (t/tau)^-alpha / Gamma(1 - alpha) over the band's times, and completely") {
  for (double alpha : {0.1, 0.4, 0.8}) {
    const runtime::SpringpotParameters p{50.0, alpha, 0.01, 0.01, 1000.0};
    const Chain chain(p);
    double worst = 0.0;
    for (double t : log_points(1.0 / (2.0 * std::numbers::pi * p.f_high), 1.0 / (2.0 * std::numbers::pi * p.f_low), 41)) {
      const double exact = p.k * std::pow(t / p.tau, -alpha) / std::tgamma(1.0 - alpha);
      worst = std::max(worst, test::relative_error(chain.relaxation(t), exact));
    }
    CAPTURE(alpha);
    CHECK(worst < 2e-3);
    CHECK(chain.relaxation(1e9) == doctest::Approx(0.0).epsilon(1e-12));
  }
}

TEST_CASE("alpha near 0 is a spring k, near 1 a dashpot k tau, in the band") {
  const double f = 3.0, w = 2.0 * std::numbers::pi * f;
  const Chain spring({80.0, 1e-3, 0.02, 0.01, 1000.0});
  CHECK(std::abs(spring.stiffness(f)) == doctest::Approx(80.0).epsilon(1e-2));
  const Chain dashpot({80.0, 0.999, 0.02, 0.01, 1000.0});
  CHECK(std::abs(dashpot.stiffness(f)) == doctest::Approx(80.0 * w * 0.02).epsilon(1e-2));
  CHECK(test::degrees(std::arg(dashpot.stiffness(f))) == doctest::Approx(89.91).epsilon(1e-3));
}

TEST_CASE("a springpot beside a yeoh spring and friction: the closed form is the limit of fixed time steps") {
  const auto net = test::network_from(R"(
    model fy {
      yeoh      y  (D10 = 40, D20 = -0.3, D30 = 0.01)
      friction  f  (k = 120, uy = 0.05 mm)
      springpot sp (k = 60, alpha = 0.25, tau = 20 ms, f_low = 0.1 Hz, f_high = 200 Hz)
    })",
                                      "fy");
  REQUIRE(runtime::has_closed_form_periodic_state(net));
  runtime::HarmonicOptions fixed;
  fixed.steady_state = runtime::SteadyState::time_stepping;
  for (double u0 : {0.02, 1.0})
    for (double f : {0.5, 10.0, 100.0}) {
      const auto exact = runtime::closed_form_harmonic_point(net, u0, f, runtime::HarmonicDefinition::thesis);
      const auto stepped = runtime::simulate_harmonic_point(net, u0, f, fixed);
      CAPTURE(u0);
      CAPTURE(f);
      CHECK(stepped.converged);
      CHECK(test::relative_error(stepped.measures.stiffness, exact.measures.stiffness) < 5e-6);
      CHECK(std::abs(stepped.measures.phase - exact.measures.phase) < 5e-6);
    }
}

TEST_CASE("a spring in series with a springpot: the chain's closed form is the exact fractional K* within the band") {
  const char* source = R"(
    model s { series { spring e (k = 100) springpot sp (k = 50, alpha = 0.3, tau = 10 ms) } })";
  const auto net = test::network_from(source, "s");
  REQUIRE(runtime::has_closed_form_periodic_state(net));
  for (double f : {0.01, 0.3, 10.0, 300.0, 1000.0}) {
    const auto chain = runtime::closed_form_harmonic_point(net, 1.0, f, runtime::HarmonicDefinition::thesis);
    const auto exact = runtime::complex_stiffness(net.model(), net.parameters(), f);
    REQUIRE(exact);
    CAPTURE(f);
    CHECK(test::relative_error(chain.measures.stiffness, std::abs(*exact)) < 5e-4);
    CHECK(std::abs(test::degrees(chain.measures.phase - std::arg(*exact))) < 0.02);
  }
}

TEST_CASE("fixed steps and IDA agree on a springpot history: a spring, a springpot and friction in series") {
  const auto network = test::network_from(R"(
    model h { series { spring e (k = 400) springpot sp (k = 60, alpha = 0.4, tau = 5 ms, f_low = 1 Hz, f_high = 100 Hz)
                       friction f (k = 500, fy = 20 N) } })",
                                          "h");
  const auto drive = runtime::quasistatic_sine({0.5}, 10.0, 2, 2000);
  const auto fixed = runtime::run_history(network, drive, true, runtime::SolverChoice::fixed);
  const auto dae = runtime::run_history(network, drive, true, runtime::SolverChoice::sundials);
  double scale = 0.0, worst = 0.0, worst_element = 0.0;
  for (std::size_t i = 0; i < drive.time.size(); ++i) {
    scale = std::max(scale, std::abs(fixed.force[i]));
    worst = std::max(worst, std::abs(fixed.force[i] - dae.force[i]));
    worst_element = std::max(worst_element, std::abs(fixed.element_force[1][i] - dae.element_force[1][i]));
  }
  REQUIRE(fixed.element_paths[1] == "sp");
  MESSAGE("springpot history: worst force difference " << worst << " N of " << scale << " N");
  CHECK(worst < 1e-3 * scale);
  CHECK(worst_element < 1e-3 * scale);
}

}  // namespace springpot_test
