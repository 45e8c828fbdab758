// The screen's objective (screen.hpp): the fitted model with elements added in parallel, sized
// by one factor each, scored as fit_scoring.hpp scores a fit, without simulating the sum.
//   harmonic   K*_m + sum_b a_b K*_b + beta        at every point (first-harmonic superposition)
//   history    F_m + sum_b a_b s_b(t) + beta u(t) + dc
// beta [N/mm] the refit of the linear stiffness, per data set; dc [N] that of a free force
// offset (fit/force_offset.hpp). A trial that explains part of the stiffness (free play engaging
// at the larger amplitudes, say) is then sized with the springs the model already has lowered to
// make room for it, as the refit will (refit.hpp, stage 1).
#pragma once

#include "runtime/fit/complex_residuals.hpp"
#include "runtime/fit/fit.hpp"
#include "runtime/fit/fit_scoring.hpp"

#include <complex>
#include <optional>
#include <vector>

namespace rheo::runtime::diagnosis {

// The added response of one trial (or one yeoh basis function) on every data set.
struct Signature {
  std::vector<std::vector<std::complex<double>>> harmonic;  // per set (empty for histories): K*_c per point
  std::vector<std::vector<double>> history;                 // per set (empty for harmonic sets): s(t) per sample
};

// Called thousands of times a screen: the fitted K*_m of every harmonic point is formed once, each
// call scores the sums K* directly (complex_residuals.hpp) and writes a history's sum into a
// scratch copy of its fitted prediction (not thread-safe).
class AddedObjective {
 public:
  // FIT: the model fitted to DATA (its predictions are read; DATA and SCORE must outlive this).
  AddedObjective(const FitResult& fit, const std::vector<FitDataSet>& data, const ScoreSettings& score);

  // The objective (sum of squared residual terms) with COEFFICIENT[b] times BASIS[b] added and
  // beta (and dc) refitted on every data set.
  double operator()(const std::vector<const Signature*>& basis, const std::vector<double>& coefficient) const;

 private:
  double harmonic_objective(std::size_t f, const std::vector<const Signature*>& basis, const std::vector<double>& coefficient) const;
  static void add_history(const FitDataSet& set, const std::vector<const Signature*>& basis, const std::vector<double>& coefficient, std::size_t f,
                          std::vector<double>& force);

  const std::vector<FitDataSet>& data_;
  const ScoreSettings& score_;
  std::vector<std::vector<std::complex<double>>> base_k_;        // per set: K*_m per harmonic point
  std::vector<std::optional<ComplexResiduals>> harmonic_terms_;  // per set (nothing for histories)
  std::vector<std::vector<double>> base_force_;                  // per set: F_m per history sample
  mutable std::vector<Prediction> scratch_;                      // per set: the fitted prediction, a history's force rewritten per call
  mutable std::vector<double> residuals_, moved_;
  mutable std::vector<std::complex<double>> trial_k_;  // per harmonic point of the set at hand: K*_m + sum a s
};

}  // namespace rheo::runtime::diagnosis
