// The measurement noise behind a fit's residual, estimated from the residual itself, and
// whether the gap (diagnose.hpp) is more than that noise.
//
// A model's systematic miss is smooth over the measurement (over amplitude and frequency on a
// grid, over time in a history); measurement noise is not. Each residual r_i with a neighbour on
// either side along one axis is compared with the straight line through them (the pseudo-
// residual of Gasser, Sroka and Jennen-Steinmetz 1986):
//   e_i = r_i - (w_- r_- + w_+ r_+),   w_- = (x_+ - x_i)/(x_+ - x_-),  w_+ = (x_i - x_-)/(x_+ - x_-),
// x the axis coordinate. A residual linear in x cancels in e_i; independent noise of variance
// s_i^2 gives E[e_i^2] = s_i^2 + w_-^2 s_-^2 + w_+^2 s_+^2, so
//   q_i = e_i^2 / (1 + w_-^2 + w_+^2)
// estimates the noise variance around point i. The noise may vary from point to point (a
// relative damping residual's grows as the phase falls, so the edge of a grid at low phase can
// hold most of it): each point's variance is the mean of the q of the pseudo-residuals it takes
// part in, and the variances are summed over every point as err sums the squares.
//
// Harmonic tables: the terms r_K and r_d of err (6.1) over the amplitude x frequency grid of all
// harmonic files; neighbours are the nearest measured levels of the same row or column, x the
// level in log or linear measure, whichever spaces the levels more evenly. A systematic residual
// that bends within the grid spacing inflates the estimate along that axis: where the two axes'
// estimates differ by more than two standard errors of their difference the lower one is taken,
// else both are pooled (for r_K, r_d and the phase separately). Pure noise leaves
//   err_noise = sqrt(sum_i s_K,i^2 + s_d,i^2) / n     (err = sqrt(sum r_K^2 + r_d^2) / n, n points).
// Histories: r = (F - F_exp)/max|F_exp| along time, neighbours the samples h either side for
// lags h = 1..32, the means fitted by noise correlated from sample to sample (AR(1)) plus a miss
// smooth over the lag (noise_estimate.cpp history_noise); pure noise
// leaves an RMS force residual of s per file, and the RMS over files as the gap takes it.
//
// Where the noise's size varies over the grid (noise_profile.hpp), the pseudo-residuals of the
// axis taken (both where pooled) fit its power law in amplitude and frequency, for r_K and the
// phase separately.
//
// The estimate's standard error is that of a mean of the q_i, sd(q) sqrt(2/m) for m of them
// (neighbouring q_i share points: their correlation doubles the variance of the mean), halved
// for the square root.
#pragma once

#include "runtime/diagnosis/noise_profile.hpp"
#include "runtime/fit/fit.hpp"

#include <vector>

namespace rheo::runtime::diagnosis {

struct NoiseEstimate {
  bool estimated = false;       // enough neighbours: at least kMinPseudoResiduals pseudo-residuals
  double floor = 0.0;           // the gap pure noise would leave, in the gap's measure
  double relative_error = 0.0;  // standard error of `floor` relative to it
  int pseudo_residuals = 0;     // m: over the axis taken (harmonic), over every history
  double stiffness = 0.0;       // harmonic: RMS noise of K/K_exp [-]
  double phase = 0.0;           // harmonic: RMS noise of the phase [rad]
  // harmonic: how the variances of K/K_exp and of the phase vary over the grid (noise_profile.hpp;
  // where they do, `stiffness` and `phase` are the RMS of the fitted profile over the points)
  NoiseProfile stiffness_profile, phase_profile;
  bool harmonic_along_frequency = false;  // harmonic: the stiffness estimate along frequency alone (else amplitude, or both)
  double force = 0.0;                     // histories: RMS force noise relative to max|F_exp| [-], RMS over files
  double autocorrelation = 0.0;           // histories: the residual's lag-1 autocorrelation (0 white, near 1 smooth)
};

inline constexpr int kMinPseudoResiduals = 8;

// The noise behind FIT's residual on DATA (the data it was fitted to).
NoiseEstimate estimate_noise(const FitResult& fit, const std::vector<FitDataSet>& data);

// Whether GAP is more than NOISE explains for a fit of P free parameters to N residual terms:
// pure noise leaves floor sqrt((N - P)/N) (the fit takes P of its N degrees of freedom), and
// GAP must exceed that by the larger of 25 % and three standard errors of the estimate.
// Without an estimate (too few neighbours) nothing can be told from noise: false.
bool systematic(double gap, const NoiseEstimate& noise, int residual_terms, int parameters);

// Whether RATIO, a residual over what noise leaves (1: at the noise), is beyond NOISE: above 1 by
// more than the larger of 25 % and three standard errors of the estimate.
bool beyond_noise_ratio(double ratio, const NoiseEstimate& noise);

// GAP over the floor pure noise would leave for a fit of P parameters to N terms (1: at the noise).
double noise_ratio(double gap, const NoiseEstimate& noise, int residual_terms, int parameters);

}  // namespace rheo::runtime::diagnosis
