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

// p of FIT: its free parameters and its fitted force offsets (one per history whose data line
// has `force_offset = free`, fit/force_offset.hpp).
int fitted_parameters(const FitResult& fit);

// BIC of FIT over N residual terms: chi^2 + p ln N when WEIGHTED, else N ln J + p ln N, p = fitted_parameters.
double criterion(const FitResult& fit, int residual_terms, bool weighted, const NoiseEstimate& noise);

// A noise-weighted BIC RICHER of a model of P parameters over N residual terms lower than the
// BIC SIMPLER of one with fewer parameters by more than kDecisiveCriterion times the
// overdispersion c = max(1, chi^2_richer / (N - P)), chi^2_richer = RICHER - P ln N: evidence
// "very strong" on Kass and Raftery's scale (J. Am. Stat. Assoc. 90, 1995: a BIC lower by more
// than 10), with the noise taken at the size of the richer fit's residual where that is beyond
// the estimate (every chi^2 difference is then c times what noise of the residual's size gives;
// the quasi-likelihood's scaling). Diagnose lets the simpler of two candidates that fit within
// its parsimony margin win unless the richer one's BIC is decisively lower (diagnose.hpp step 4).
inline constexpr double kDecisiveCriterion = 10.0;
bool decisively_lower(double richer, double simpler, int parameters, int residual_terms);

// The same by more than kPositiveCriterion times c: evidence "positive" on that scale (a BIC
// lower by more than 2; below that "not worth more than a bare mention"). Diagnose lets the
// simpler of two candidates whose gaps lie beyond its parsimony margin win unless the richer
// one's BIC is positively lower (diagnose.hpp step 4): a richer refit whose BIC is lower by
// 1.2 has not shown that its parameter is needed.
inline constexpr double kPositiveCriterion = 2.0;
bool positively_lower(double richer, double simpler, int parameters, int residual_terms);

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
// SETTINGS' harmonic options and time limit; FIT's own chi^2 and values where the search finds
// nothing lower. Requires noise_weighted(DATA, NOISE).
struct LeastChiSquare {
  double chi_square = 0.0;
  std::vector<double> values;  // every model parameter (Network::parameters() order) where it is reached
};
LeastChiSquare least_chi_square(const FitResult& fit, const std::vector<FitDataSet>& data, const NoiseEstimate& noise, const FitSettings& settings,
                                int evaluations);

// FIT's model with every parameter at VALUES and its exact response to DATA (FitResult::network
// and datasets; the rest of FIT's result is kept): the residual of another point of the search.
FitResult fit_at(const FitResult& fit, const std::vector<double>& values, const std::vector<FitDataSet>& data, const HarmonicOptions& harmonic);

// The noise behind FIT's residual and its least chi^2, estimated together. The residual of eq.
// 5.1's fit bends through the phase noise of a few nearly elastic points, and estimate_noise
// takes that bend for noise (pure noise of 0.15 deg: estimated up to 2.3 times larger); the
// residual at the likelihood's maximum holds less of it. From NOISE (estimated on FIT's
// residual): the least chi^2 (EVALUATIONS), the noise estimated again on the residual where it
// is reached, and while that changes the ratio of stiffness to phase noise, which sets the
// weights of chi^2, by more than kNoiseRatioChange, the least chi^2 again from there under the
// new estimate (at most kNoiseRounds rounds in all, half the evaluations each after the first).
// The chi^2 returned is the lower of FIT's and the last point's under the last estimate. A
// round's estimate is not taken where it leaves the criterion unweighted, or where the residual
// it came from is beyond it (beyond_noise_ratio of chi_square_ratio): a fit weighted to a term
// whose noise is near 0 (phases measured without noise) follows that term, and its residual,
// smoother still, would give a smaller noise again (pure force-amplitude noise without phase
// noise: chi^2 / (N - p) 0.84 under the first estimate, 3.6 under the re-estimate). Requires
// noise_weighted(DATA, NOISE).
struct NoiseAndChiSquare {
  NoiseEstimate noise;
  double chi_square = 0.0;
  int rounds = 0;  // least chi^2 searches run
};
inline constexpr double kNoiseRatioChange = 0.1;  // in ln(s_K / s_phi)
inline constexpr int kNoiseRounds = 3;
NoiseAndChiSquare noise_at_likelihood_maximum(const FitResult& fit, const std::vector<FitDataSet>& data, const NoiseEstimate& noise,
                                              const FitSettings& settings, int evaluations);

// A fit's residual as the verdict weighs it: its gap (diagnose.hpp), its chi^2 under the noise
// (where the criterion is noise-weighted) and its free parameters.
struct Residual {
  double gap = 0.0, chi_square = 0.0;
  int parameters = 0;
};

// RESIDUAL over what noise alone leaves (1: at the noise) for N residual terms: where WEIGHTED,
// sqrt(chi^2 / (N - p)) (chi_square_ratio), else the gap over the floor (noise_ratio); +inf for
// a positive gap where the estimated floor is 0, 0 without an estimate.
double residual_ratio(const Residual& residual, const NoiseEstimate& noise, int residual_terms, bool weighted);

// Whether a candidate took the model's residual BEFORE, beyond the noise (beyond_noise_ratio of
// residual_ratio), to the noise (AFTER not beyond it): a residual just beyond the noise cannot
// fall by a fixed share, yet a candidate that leaves only noise explains all of it. Judged as
// the verdict none / unexplained is: on chi^2 where WEIGHTED, else on the gap. Without an
// estimate nothing can be told from noise: false.
bool reaches_noise(const Residual& before, const Residual& after, const NoiseEstimate& noise, int residual_terms, bool weighted);

// Whether AFTER lowers BEFORE's residual by SHARE (DiagnoseSettings::min_improvement): its gap
// falls by SHARE, or, where WEIGHTED, its residual over the noise, sqrt(chi^2 / (N - p))
// (chi_square_ratio), does, as the verdict weighs a residual. Eq. 6.1's gap weighs every point
// alike; where the noise differs from point to point (force-amplitude noise: a relative
// stiffness noise 40 times larger at the smallest amplitude than at the largest) the gap of a
// model can sit at what the noisiest points leave while a systematic miss at the quiet points
// holds most of chi^2 (free play engaging at the largest amplitude only: the gap 0.052 ->
// 0.043, chi^2 2523 -> 504 for N = 70).
bool lowers_residual(const Residual& before, const Residual& after, double share, int residual_terms, bool weighted);

}  // namespace rheo::runtime::diagnosis
