// The information criterion by which a candidate earns its parameters (diagnose.hpp, step 4):
// BIC = -2 ln L + p ln N, the likelihood of a fit's N residual terms under Gaussian noise, p its
// free parameters.
//
// With a noise estimate on harmonic data (noise_estimate.hpp) the terms' variances are known and
//   -2 ln L = chi^2 = sum_i r_K,i^2 / s_K^2 + r_d,i^2 / s_d,i^2     (+ a constant, dropped),
// r_K = K/K_exp - 1 with the relative stiffness noise s_K, and the damping term of eq. 5.1,
// r_d = sin(phi)/sin(phi_exp) - 1, carrying a phase noise e of absolute size s_phi:
//   r_d = cot(phi_exp) e - e^2/2 + ...,   s_d,i^2 = s_phi^2 cot^2(phi_exp,i) + s_phi^4/2,
// the second-order part being what remains near 90 deg. The noise of a damping term grows as the
// phase falls, so eq. 5.1's unweighted sum lets a few nearly elastic points dominate: an extra
// element that bends the model through their noise lowers the gap while the likelihood falls
// (pure-noise data: gap 0.018 -> 0.010 with chi^2 70.7 -> 94.4 for N = 72).
// Without an estimate (too few neighbours, or histories, whose force noise is one size per file)
// the variance is unknown and profiled out: -2 ln L = N ln(J/N) + const, J the fit's objective,
// i.e. BIC = N ln J + p ln N up to a constant.
#pragma once

#include "runtime/diagnosis/noise_estimate.hpp"
#include "runtime/fit/fit.hpp"

#include <vector>

namespace rheo::runtime::diagnosis {

// N: two terms per harmonic point, one per history sample.
int residual_terms(const std::vector<FitDataSet>& data);

// Whether the criterion weighs the terms by NOISE: every data set harmonic and both the
// stiffness and the phase noise estimated above zero.
bool noise_weighted(const std::vector<FitDataSet>& data, const NoiseEstimate& noise);

// chi^2 of FIT's harmonic residuals under NOISE (above); requires noise.stiffness, noise.phase > 0.
double noise_chi_square(const FitResult& fit, const NoiseEstimate& noise);

// Jacobians of a least_chi_square search from one start (as refit.hpp kLocalJacobians).
inline constexpr int kLikelihoodJacobians = 10;

// sqrt(CHI_SQUARE / (N - P)): 1 where a fit of P parameters to N terms leaves only the noise.
double chi_square_ratio(double chi_square, int residual_terms, int parameters);

// BIC of FIT over N residual terms: chi^2 + p ln N when WEIGHTED, else N ln J + p ln N.
double criterion(const FitResult& fit, int residual_terms, bool weighted, const NoiseEstimate& noise);

// The least chi^2 under NOISE over FIT's free parameters, searched from FIT's values: the
// -2 ln L at the likelihood's maximum, which the BIC assumes. A fit minimises eq. 5.1, whose
// damping terms weigh a point by 1/sin^2(phase_exp) however noisy it is, so near the few nearly
// elastic points its optimum is not the likelihood's, and a larger model's fit can stay closer
// to the likelihood's optimum for no other reason than the freedom it has to follow those
// points (pure-noise data: the base fit at chi^2 98, a slider-capped Maxwell arm at 63, where
// the base model's least chi^2 is 51 and the arm's 47), or the fit may sit in another basin
// (pure noise: a Maxwell element fitted as a dashpot at tau's bound, chi^2 1122 where the
// model's least is 31). Levenberg-Marquardt on the terms r/s of chi^2 from FIT's values and
// from where FIT started (FitResult::start_values), at most EVALUATIONS evaluations in all under
// SETTINGS' harmonic options and time limit; FIT's own chi^2 where the search finds nothing
// lower. Requires noise_weighted(DATA, NOISE).
double least_chi_square(const FitResult& fit, const std::vector<FitDataSet>& data, const NoiseEstimate& noise, const FitSettings& settings,
                        int evaluations);

}  // namespace rheo::runtime::diagnosis
