#include "runtime/diagnosis/criterion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rheo::runtime::diagnosis {

int residual_terms(const std::vector<FitDataSet>& data) {
  int n = 0;
  for (const auto& set : data) n += set.is_harmonic() ? 2 * static_cast<int>(set.harmonic().size()) : static_cast<int>(set.history().force.size());
  return n;
}

bool noise_weighted(const std::vector<FitDataSet>& data, const NoiseEstimate& noise) {
  const bool all_harmonic = std::all_of(data.begin(), data.end(), [](const FitDataSet& set) { return set.is_harmonic(); });
  return all_harmonic && noise.estimated && noise.stiffness > 0.0 && noise.phase > 0.0;
}

double noise_chi_square(const FitResult& fit, const NoiseEstimate& noise) {
  const double s_k2 = noise.stiffness * noise.stiffness, s_phi2 = noise.phase * noise.phase;
  double chi2 = 0.0;
  for (const auto& set : fit.datasets) {
    if (!set.harmonic) continue;
    for (std::size_t i = 0; i < set.residuals.stiffness.size(); ++i) {
      chi2 += set.residuals.stiffness[i] * set.residuals.stiffness[i] / s_k2;
      const double phase = set.measured_phase[i];
      if (!(phase > 0.0 && phase < std::numbers::pi)) continue;  // its damping term is left out of eq. 5.1
      const double cot = std::cos(phase) / std::sin(phase);
      chi2 += set.residuals.damping[i] * set.residuals.damping[i] / (s_phi2 * cot * cot + 0.5 * s_phi2 * s_phi2);
    }
  }
  return chi2;
}

double criterion(const FitResult& fit, int residual_terms, bool weighted, const NoiseEstimate& noise) {
  const double n = static_cast<double>(residual_terms);
  const double penalty = static_cast<double>(fit.free.size()) * std::log(n);
  if (weighted) return noise_chi_square(fit, noise) + penalty;
  return n * std::log(std::max(fit.objective, 1e-300)) + penalty;
}

}  // namespace rheo::runtime::diagnosis
