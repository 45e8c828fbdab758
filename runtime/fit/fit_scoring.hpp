// How a parameter set is scored against the measurements of a fit: the model's response at
// every data point, and the weighted residual vector whose sum of squares is the objective.
//
// Each file f contributes w_f * mean_j(r_j^2) (its residuals scaled by sqrt(w_f / m_f), m_f the
// number of its residual terms), so files of different sizes and kinds count alike unless
// weighted. Residual terms:
//   harmonic, objective phi (eq. 5.38; 5.1 when both weights are 1), per point:
//     sqrt(w_K) (K / K_exp - 1),   sqrt(w_d) (d / d_exp - 1),   d = sin(phase)
//   harmonic, objective least_squares (relative, on the complex stiffness K* = K e^{i phase}):
//     (K' - K'_exp) / |K*_exp|,    (K'' - K''_exp) / |K*_exp|
//   history (either objective), per sample: (F - F_exp) / max|F_exp|, F with the data line's
//     force offset (force_offset.hpp)
// A harmonic table's optional `weight` column multiplies its point's squared terms.
// For one harmonic file and objective phi the minimiser is that of eq. 5.38.
//
// Model response of harmonic files by the method chosen (histories are always simulated):
//   exact        the periodic steady state (closed form, or time stepping where nested)
//   approximate  the thesis's analytical approximation, eqs. 5.5-5.21
//   corrected    the approximation calibrated by time-stepping factors, eqs. 5.2-5.4
#pragma once

#include "lang/fit_settings.hpp"
#include "runtime/protocols/run_history.hpp"
#include "runtime/io/fit_data.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/fit/thesis_approximation.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

namespace rheo::runtime {

using lang::FitMethod;     // the `method` setting's vocabulary (lang/fit_settings.hpp)
using lang::FitObjective;  // the `objective` setting's

struct ScoreSettings {
  FitObjective objective = FitObjective::phi;
  double stiffness_weight = 1.0;  // w_K of eq. 5.38 (k)
  double damping_weight = 1.0;    // w_d (1 - k)
  FitMethod method = FitMethod::exact;
  HarmonicOptions harmonic;
};

// Harmonic point I's factor in its set's residual terms: sqrt(set weight / 2 n), times the square
// root of the point's own weight where the file gives one.
inline double harmonic_point_scale(const FitDataSet& set, std::size_t i) {
  const HarmonicData& d = set.harmonic();
  const double scale = std::sqrt(set.weight / (2.0 * static_cast<double>(d.size())));
  return d.weight.empty() ? scale : scale * std::sqrt(d.weight[i]);
}

struct Prediction {
  std::vector<HarmonicPoint> points;  // harmonic file: one per data point, same order
  std::vector<double> force;          // history file: model force at each sample [N], its offset included
  double force_offset = 0.0;          // history file: the offset in `force` [N] (force_offset.hpp)
};

// Which force offsets a history's prediction carries.
enum class Offsets : std::uint8_t {
  applied,   // the declared ones, and the free ones at their least-squares value for this prediction
  declared,  // the declared ones; a free one left at 0 (the caller supplies it)
  none,      // none: the network's force alone
};

// `correction` (one per harmonic file, same order as the harmonic files in the fit) is used by
// FitMethod::corrected and must then be given. A history's force carries the offsets OFFSETS
// says (force_offset.hpp).
Prediction predict(const Network& network, const FitDataSet& set, FitMethod method, const HarmonicOptions& harmonic,
                   const ThesisCorrection* correction, Offsets offsets = Offsets::applied);

// Appends the weighted residual terms of one file (see above) to `out`; a harmonic table's
// points spread over settings.harmonic.threads threads (parallel_for.hpp), the same terms for
// every count.
void append_residuals(const FitDataSet& set, const Prediction& prediction, const ScoreSettings& settings, std::vector<double>& out);

}  // namespace rheo::runtime
