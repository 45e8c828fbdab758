// The information criterion of rheo diagnose (runtime/diagnosis/criterion.hpp): chi^2 under the
// estimated noise against a hand computation and against its own noise model (pure noise gives
// chi^2 ~ N, also with points near 90 deg), and the unweighted BIC where there is no estimate.
#include "runtime/diagnosis/criterion.hpp"

#include "portable_random.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

namespace criterion_test {

using namespace rheo;
namespace dx = runtime::diagnosis;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A fit to harmonic points measured at PHASES [rad] with the given relative residuals.
runtime::FitResult harmonic_fit(const std::vector<double>& phases, const std::vector<double>& r_k, const std::vector<double>& r_d) {
  runtime::FitResult fit{test::network_from("model m { spring s (k = 1 N/mm in [0.1, 10]) }", "m")};
  runtime::DataSetFit set;
  set.measured_phase = phases;
  set.measured_stiffness.assign(phases.size(), 100.0);
  set.residuals.stiffness = r_k;
  set.residuals.damping = r_d;
  fit.datasets.push_back(set);
  fit.free = {0};
  return fit;
}

dx::NoiseEstimate noise_of(double stiffness, double phase) {
  dx::NoiseEstimate n;
  n.estimated = true, n.stiffness = stiffness, n.phase = phase;
  return n;
}

}  // namespace

TEST_CASE("diagnose criterion: chi^2 weighs each term by its noise, the damping term's by s_phi^2 cot^2 phi + s_phi^4/2") {
  const double s_k = 0.01, s_phi = 0.002;
  const auto fit = harmonic_fit({30.0 * kDeg, 90.0 * kDeg, 0.0}, {0.01, -0.02, 0.03}, {0.005, 0.001, 0.4});
  // 30 deg: cot^2 = 3; 90 deg: cot = 0, only the second-order part; 0 deg: damping term left out.
  const double expected = 1.0 + 4.0 + 9.0 + 0.005 * 0.005 / (s_phi * s_phi * 3.0 + 0.5 * std::pow(s_phi, 4)) +
                          0.001 * 0.001 / (0.5 * std::pow(s_phi, 4));
  CHECK(dx::noise_chi_square(fit, noise_of(s_k, s_phi)) == doctest::Approx(expected).epsilon(1e-12));
  const int n = 6;
  CHECK(dx::criterion(fit, n, true, noise_of(s_k, s_phi)) == doctest::Approx(expected + std::log(6.0)).epsilon(1e-12));
}

TEST_CASE("diagnose criterion: residuals drawn from the noise model give chi^2 within 4 standard deviations of N, also near 90 deg") {
  const double s_k = 0.01, s_phi = 0.15 * kDeg;
  for (const double top : {20.0, 89.9}) {  // phases from 0.5 deg up to TOP
    test::PortableRandom random(7);
    std::vector<double> phases, r_k, r_d;
    for (int i = 0; i < 2000; ++i) {
      const double phase = (0.5 + (top - 0.5) * i / 1999.0) * kDeg;
      phases.push_back(phase);
      r_k.push_back(s_k * random.normal());
      r_d.push_back(std::sin(phase + s_phi * random.normal()) / std::sin(phase) - 1.0);
    }
    const double n = 2.0 * static_cast<double>(phases.size());
    CAPTURE(top);
    CHECK(std::abs(dx::noise_chi_square(harmonic_fit(phases, r_k, r_d), noise_of(s_k, s_phi)) - n) < 4.0 * std::sqrt(2.0 * n));
    // The same noise judged 30 % smaller is far outside: the test can tell the variances apart.
    CHECK(dx::noise_chi_square(harmonic_fit(phases, r_k, r_d), noise_of(0.7 * s_k, 0.7 * s_phi)) - n > 10.0 * std::sqrt(2.0 * n));
  }
}

TEST_CASE("diagnose criterion: without a noise estimate or with histories, BIC = N ln J + p ln N") {
  auto fit = harmonic_fit({0.1}, {0.01}, {0.02});
  fit.objective = 0.25;
  CHECK(dx::criterion(fit, 2, false, {}) == doctest::Approx(2.0 * std::log(0.25) + std::log(2.0)).epsilon(1e-12));
  runtime::HarmonicData h;
  h.amplitude = {1.0}, h.frequency = {1.0}, h.stiffness = {100.0}, h.phase = {0.1}, h.rows = {2};
  const runtime::FitDataSet harmonic{"grid.csv", 1.0, h, {}};
  CHECK(dx::residual_terms({harmonic}) == 2);
  CHECK(dx::noise_weighted({harmonic}, noise_of(0.01, 0.002)));
  CHECK_FALSE(dx::noise_weighted({harmonic}, dx::NoiseEstimate{}));  // not estimated
  CHECK_FALSE(dx::noise_weighted({harmonic}, noise_of(0.01, 0.0)));
  runtime::HistoryData history;
  history.force = {1.0, 2.0, 3.0};
  const runtime::FitDataSet samples{"history.csv", 1.0, history, {}};
  CHECK(dx::residual_terms({harmonic, samples}) == 5);
  CHECK_FALSE(dx::noise_weighted({harmonic, samples}, noise_of(0.01, 0.002)));
}

TEST_CASE("diagnose criterion, unweighted: a candidate that takes a gap just beyond the noise to the noise reaches it") {
  // Floor 0.003 +- 2 %, N = 4000 terms: the bar for systematic is 1.25 x floor sqrt((N - P)/N).
  dx::NoiseEstimate n;
  n.estimated = true, n.floor = 0.003, n.relative_error = 0.02;
  const double bar = 1.25 * 0.003 * std::sqrt((4000.0 - 5.0) / 4000.0);
  auto reaches = [&](double before, double after) { return dx::reaches_noise({before, 0.0, 5}, {after, 0.0, 7}, n, 4000, false); };
  // 1.27 x the floor to 1.0 x: 21 % lower, short of a 25 % cut, but only noise is left.
  CHECK(reaches(1.27 * 0.003, 0.003));
  CHECK(reaches(1.01 * bar, 0.99 * bar));
  // A gap already at the noise is not reached, and one still beyond it is not either.
  CHECK_FALSE(reaches(0.99 * bar, 0.003));
  CHECK_FALSE(reaches(2.0 * 0.003, 1.3 * 0.003));
  CHECK(dx::residual_ratio({1.27 * 0.003, 0.0, 5}, n, 4000, false) == doctest::Approx(1.27 / std::sqrt(3995.0 / 4000.0)).epsilon(1e-12));
  // Without an estimate nothing is told from noise.
  n.estimated = false;
  CHECK_FALSE(reaches(1.27 * 0.003, 0.003));
}

// Where the criterion is noise-weighted the verdict tells noise from a systematic residual by
// sqrt(chi^2 / (N - p)), and so does reaches_noise: err (6.1) of eq. 5.1's fit can be twice the
// floor on pure noise (a fit drawn through nearly elastic points' phase noise), and err can sit
// at the floor while chi^2 says the residual is systematic.
TEST_CASE("diagnose criterion, weighted: reaches_noise judges on chi^2 over N - p, not on the gap") {
  dx::NoiseEstimate n = noise_of(0.01, 0.002);
  n.floor = 0.003, n.relative_error = 0.02;
  const int terms = 400;
  // Pure noise whose fit's err is twice the floor: chi^2 = N - p, at the noise. A candidate
  // that brings err to the floor reaches nothing (judged on the gap, it would).
  CHECK_FALSE(dx::reaches_noise({2.0 * 0.003, 395.0, 5}, {0.003, 390.0, 7}, n, terms, true));
  CHECK(dx::reaches_noise({2.0 * 0.003, 395.0, 5}, {0.003, 390.0, 7}, n, terms, false));
  // A residual beyond the noise by chi^2 (ratio 1.4) whose err is at the floor: a candidate
  // that takes chi^2 to N - p reaches the noise (judged on the gap, it would not).
  CHECK(dx::reaches_noise({1.02 * 0.003, 1.96 * 395.0, 5}, {1.0 * 0.003, 393.0, 7}, n, terms, true));
  CHECK_FALSE(dx::reaches_noise({1.02 * 0.003, 1.96 * 395.0, 5}, {1.0 * 0.003, 393.0, 7}, n, terms, false));
  // And one that leaves chi^2 beyond the noise (ratio 1.3) does not.
  CHECK_FALSE(dx::reaches_noise({1.02 * 0.003, 1.96 * 395.0, 5}, {1.0 * 0.003, 1.69 * 393.0, 7}, n, terms, true));
  CHECK(dx::residual_ratio({0.003, 1.96 * 395.0, 5}, n, terms, true) == doctest::Approx(1.4).epsilon(1e-12));
}

// decisively_lower: BIC_simpler - BIC_richer > 10 c, c = max(1, chi^2_richer / (N - p)),
// chi^2_richer = BIC_richer - p ln N. N = 100, p = 8: ln 100 = 4.60517.
TEST_CASE("diagnose criterion: a richer model's lower BIC is decisive beyond 10 times the overdispersion of its residual") {
  const int n = 100, p = 8;
  const double penalty = p * std::log(100.0);
  // chi^2 = 92 = N - p: c = 1, the margin 10.
  CHECK(dx::decisively_lower(92.0 + penalty, 92.0 + penalty + 10.01, p, n));
  CHECK_FALSE(dx::decisively_lower(92.0 + penalty, 92.0 + penalty + 9.99, p, n));
  // chi^2 = 46 < N - p: c stays 1.
  CHECK(dx::decisively_lower(46.0 + penalty, 46.0 + penalty + 10.01, p, n));
  // chi^2 = 920: c = 10, the margin 100.
  CHECK(dx::decisively_lower(920.0 + penalty, 920.0 + penalty + 100.1, p, n));
  CHECK_FALSE(dx::decisively_lower(920.0 + penalty, 920.0 + penalty + 99.9, p, n));
  // A higher BIC is never decisively lower.
  CHECK_FALSE(dx::decisively_lower(920.0 + penalty, 900.0 + penalty, p, n));
}

// positively_lower: the same with 2 c. The friction and capped Maxwell refits of a hidden
// friction element (diagnosis_sweep_test.cpp, seed 8): BIC 82.8 (p 5) and 81.6 (p 6) over 50
// terms, 1.2 apart: not positive evidence for the richer (c = (81.6 - 6 ln 50) / 44 = 1.32).
TEST_CASE("diagnose criterion: a richer model's lower BIC is positive evidence beyond 2 times the overdispersion of its residual") {
  const int n = 100, p = 8;
  const double penalty = p * std::log(100.0);
  CHECK(dx::positively_lower(92.0 + penalty, 92.0 + penalty + 2.01, p, n));
  CHECK_FALSE(dx::positively_lower(92.0 + penalty, 92.0 + penalty + 1.99, p, n));
  CHECK(dx::positively_lower(920.0 + penalty, 920.0 + penalty + 20.1, p, n));
  CHECK_FALSE(dx::positively_lower(920.0 + penalty, 920.0 + penalty + 19.9, p, n));
  CHECK_FALSE(dx::positively_lower(81.6, 82.8, 6, 50));
  CHECK(dx::positively_lower(81.6, 82.8 + 1.5, 6, 50));        // 2.7 apart
  CHECK_FALSE(dx::positively_lower(81.6, 82.8 + 1.4, 6, 50));  // 2.6 apart
}

// lowers_residual: the gap falls by the share, or where weighted sqrt(chi^2 / (N - p)) does.
// N = 70: before chi^2 2523 over 65 (ratio 6.230), after 504 over 63 (ratio 2.828, 55 % lower),
// the gap 0.052 -> 0.0435 (16 % lower).
TEST_CASE("diagnose criterion: a residual falls by the share in its gap, or where weighted in sqrt(chi^2 / (N - p))") {
  const dx::Residual before{0.052, 2523.0, 5}, after{0.0435, 504.0, 7};
  CHECK(dx::lowers_residual(before, after, 0.25, 70, true));
  CHECK_FALSE(dx::lowers_residual(before, after, 0.25, 70, false));
  CHECK_FALSE(dx::lowers_residual(before, after, 0.6, 70, true));  // 55 % is not 60 %
  // The gap alone, weighted or not: 0.052 -> 0.039 is 25 %.
  const dx::Residual gap_only{0.039, 2523.0, 7};
  CHECK(dx::lowers_residual(before, gap_only, 0.25, 70, true));
  CHECK(dx::lowers_residual(before, gap_only, 0.25, 70, false));
  // chi^2 / (N - p) exactly 0.75^2 of before's: the boundary holds.
  const dx::Residual boundary{0.052, 2523.0 / 65.0 * 0.5625 * 63.0, 7};
  CHECK(dx::lowers_residual(before, boundary, 0.25 - 1e-12, 70, true));
  CHECK_FALSE(dx::lowers_residual(before, boundary, 0.25 + 1e-9, 70, true));
}

}  // namespace criterion_test
