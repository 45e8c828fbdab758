// How the size of harmonic measurement noise varies over the amplitude x frequency grid: one size
// everywhere, or a power law in amplitude and frequency where the pseudo-residuals
// (noise_estimate.hpp) show it.
//
// A rig's force noise is often of fixed size in newtons: the relative noise of K = F/u is then
// s_F/(K u), several times larger at the smallest amplitude than at the largest, and the phase's
// likewise. Weighed as if of one size, the noisy small amplitudes dominate chi^2, and a candidate
// that bends the model through them earns (pure noise of 0.95 % force-amplitude noise on a 5 x 6
// grid: a slider-capped Maxwell arm named). The variance is modelled as
//   v(a, f) = exp(t0 + t1 x_a + t2 x_f),   x_a = ln(a) - mean ln(a), x_f = ln(f) - mean ln(f)
// (means over the points), fitted to the pseudo-residuals' q_j: each is v's weighted mean over
// its three points, E[q_j] = mu_j = sum_k c_jk v(a_k, f_k), c = (1, w_-^2, w_+^2)/(1 + w_-^2 +
// w_+^2), and q_j / mu_j is chi^2 with one degree of freedom, so the likelihood is maximised over
// -2 ln L = sum_j ln mu_j + q_j / mu_j (Fisher scoring). The power law is taken only where it
// beats one size by the likelihood ratio D = -2 ln L(one size) + 2 ln L(power law) > kProfileTest:
// neighbouring q share points (their correlation about doubles D's spread), so the bar is twice
// chi^2(2 degrees of freedom)'s 0.1 % point, 13.8; heavy-tailed noise and a systematic residual
// that bends within the grid spacing can pass it too, and then down-weigh where they are.
#pragma once

#include <vector>

namespace rheo::runtime::diagnosis {

inline constexpr double kProfileTest = 2.0 * 13.8;

// One pseudo-residual for the fit: its q and its three points' (amplitude [mm], frequency [Hz],
// weight c) in the order (middle, low neighbour, high neighbour).
struct ProfileTerm {
  double q = 0.0;
  double amplitude[3]{}, frequency[3]{}, weight[3]{};
};

// The relative variance v(a, f) / mean over the points of v: 1 everywhere where one size is taken.
struct NoiseProfile {
  bool varies = false;              // the power law passed kProfileTest
  double amplitude_slope = 0.0;     // t1: d ln v / d ln a
  double frequency_slope = 0.0;     // t2: d ln v / d ln f
  double log_a = 0.0, log_f = 0.0;  // the means of ln a and ln f over the points
  double scale = 1.0;               // 1 / mean over the points of exp(t1 x_a + t2 x_f)
  double deviance = 0.0;            // D of the likelihood-ratio test
  double mean_variance = 0.0;       // the fitted v's mean over the points (where it varies)
  double factor(double amplitude, double frequency) const;
};

// The profile of TERMS over the measured POINTS ((amplitude, frequency) pairs; mean of the factor
// over them 1). Fewer than 2 q per parameter, or a fit that does not converge: one size.
NoiseProfile fit_noise_profile(const std::vector<ProfileTerm>& terms, const std::vector<std::pair<double, double>>& points);

}  // namespace rheo::runtime::diagnosis
