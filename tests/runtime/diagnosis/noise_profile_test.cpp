// The noise profile of rheo diagnose (runtime/diagnosis/noise_profile.hpp) on pseudo-residuals
// drawn from a known variance law: q = mu chi^2_1 with mu the weighted mean of v(a, f) over three
// neighbouring points along frequency. A power law in amplitude and frequency is recovered and
// taken; one size everywhere is not taken for a power law.
#include "runtime/diagnosis/noise_profile.hpp"

#include "portable_random.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <utility>
#include <vector>

namespace noise_profile_test {

using namespace rheo;
namespace dx = runtime::diagnosis;

namespace {

const std::vector<double> kAmplitudes{0.03, 0.07, 0.2, 0.5, 1.0, 2.5};  // mm
const std::vector<double> kFrequencies{1, 2, 4, 7, 12, 20, 35, 50};     // Hz

// Pseudo-residuals along frequency (middle, low, high) of a grid whose variance is
// v(a, f) = a^SLOPE_A f^SLOPE_F, each q = mu * z^2, and the grid's points.
std::pair<std::vector<dx::ProfileTerm>, std::vector<std::pair<double, double>>> draw(double slope_a, double slope_f, unsigned seed) {
  test::PortableRandom random(seed);
  std::vector<dx::ProfileTerm> terms;
  std::vector<std::pair<double, double>> points;
  auto v = [&](double a, double f) { return std::pow(a, slope_a) * std::pow(f, slope_f); };
  for (double a : kAmplitudes) {
    for (double f : kFrequencies) points.emplace_back(a, f);
    for (std::size_t i = 1; i + 1 < kFrequencies.size(); ++i) {
      const double xl = std::log(kFrequencies[i - 1]), x = std::log(kFrequencies[i]), xh = std::log(kFrequencies[i + 1]);
      const double wl = (xh - x) / (xh - xl), wh = (x - xl) / (xh - xl), norm = 1.0 + wl * wl + wh * wh;
      dx::ProfileTerm t;
      const double f3[3]{kFrequencies[i], kFrequencies[i - 1], kFrequencies[i + 1]}, c3[3]{1.0 / norm, wl * wl / norm, wh * wh / norm};
      double mu = 0.0;
      for (int k = 0; k < 3; ++k) t.amplitude[k] = a, t.frequency[k] = f3[k], t.weight[k] = c3[k], mu += c3[k] * v(a, f3[k]);
      const double z = random.normal();
      t.q = mu * z * z;
      terms.push_back(t);
    }
  }
  return {terms, points};
}

}  // namespace

TEST_CASE("noise profile: a variance falling as a^-2 (force noise of fixed size) and rising as f^0.5 is recovered and taken") {
  for (unsigned seed : {1u, 2u, 3u}) {
    const auto [terms, points] = draw(-2.0, 0.5, seed);
    const dx::NoiseProfile p = dx::fit_noise_profile(terms, points);
    CAPTURE(seed);
    REQUIRE(p.varies);
    CHECK(p.amplitude_slope == doctest::Approx(-2.0).epsilon(0.15));
    CHECK(p.frequency_slope == doctest::Approx(0.5).epsilon(0.6).scale(0.0));
    // The factor's mean over the points is 1, and its ratio between two points is the law's.
    double mean = 0.0;
    for (const auto& [a, f] : points) mean += p.factor(a, f);
    CHECK(mean / static_cast<double>(points.size()) == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(p.factor(0.03, 12.0) / p.factor(2.5, 12.0) == doctest::Approx(std::pow(0.03 / 2.5, p.amplitude_slope)).epsilon(1e-9));
  }
}

TEST_CASE("noise profile: noise of one size gives no profile (factor 1) over ten draws") {
  int taken = 0;
  for (unsigned seed = 10; seed < 20; ++seed) {
    const auto [terms, points] = draw(0.0, 0.0, seed);
    const dx::NoiseProfile p = dx::fit_noise_profile(terms, points);
    taken += p.varies;
    if (!p.varies) CHECK(p.factor(0.03, 1.0) == 1.0);
  }
  CHECK(taken == 0);
  // Too few pseudo-residuals for three parameters: one size.
  const auto [terms, points] = draw(-2.0, 0.0, 4);
  CHECK_FALSE(dx::fit_noise_profile({terms.begin(), terms.begin() + 5}, points).varies);
}

}  // namespace noise_profile_test
