#include "runtime/diagnosis/criterion.hpp"

#include "runtime/fit/fit_coordinates.hpp"
#include "runtime/fit/fit_scoring.hpp"
#include "runtime/fit/fit_search.hpp"

#include <algorithm>
#include <chrono>
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

namespace {

// The variance of a damping term r_d at the measured phase PHASE under NOISE (criterion.hpp);
// 0 where eq. 5.1 leaves the term out (phase outside (0, pi)).
double damping_variance(double phase, const NoiseEstimate& noise) {
  if (!(phase > 0.0 && phase < std::numbers::pi)) return 0.0;
  const double s_phi2 = noise.phase * noise.phase, cot = std::cos(phase) / std::sin(phase);
  return s_phi2 * cot * cot + 0.5 * s_phi2 * s_phi2;
}

}  // namespace

double noise_chi_square(const FitResult& fit, const NoiseEstimate& noise) {
  const double s_k2 = noise.stiffness * noise.stiffness;
  double chi2 = 0.0;
  for (const auto& set : fit.datasets) {
    if (!set.harmonic) continue;
    for (std::size_t i = 0; i < set.residuals.stiffness.size(); ++i) {
      chi2 += set.residuals.stiffness[i] * set.residuals.stiffness[i] / s_k2;
      if (const double v = damping_variance(set.measured_phase[i], noise); v > 0.0) chi2 += set.residuals.damping[i] * set.residuals.damping[i] / v;
    }
  }
  return chi2;
}

double least_chi_square(const FitResult& fit, const std::vector<FitDataSet>& data, const NoiseEstimate& noise, const FitSettings& settings,
                        int evaluations) {
  const double own = noise_chi_square(fit, noise);
  if (fit.free.empty() || evaluations <= static_cast<int>(fit.free.size())) return own;
  const Coordinates coordinates(fit.network, fit.free);
  const Residuals terms = [&](const std::vector<double>& z) {
    const Network network = coordinates.network(z);
    std::vector<double> r;
    for (const FitDataSet& set : data) {
      const HarmonicData& d = set.harmonic();
      const Prediction p = predict(network, set, FitMethod::exact, settings.score.harmonic, nullptr);
      for (std::size_t i = 0; i < d.size(); ++i) {
        const CycleMeasures& m = p.points[i].measures;
        r.push_back((m.stiffness / d.stiffness[i] - 1.0) / noise.stiffness);
        const double v = damping_variance(d.phase[i], noise);
        r.push_back(v > 0.0 ? (std::sin(m.phase) / std::sin(d.phase[i]) - 1.0) / std::sqrt(v) : 0.0);
      }
    }
    return r;
  };
  SearchSettings search = settings.search;
  search.algorithm.reset(), search.starts = 1, search.samples = 0, search.extra_starts.clear();
  search.max_evaluations = evaluations;
  search.crawl_tolerance = 1e-3;  // of chi^2 ~ N: far below the ln N a parameter costs
  if (!fit.start_values.empty()) search.extra_starts = {coordinates.z_of(fit.start_values)};
  if (settings.time_limit)
    search.deadline = std::chrono::steady_clock::now() +
                      std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(*settings.time_limit));
  const SearchResult found = search_least_squares(terms, coordinates.z0, coordinates.lower, coordinates.upper, coordinates.logarithmic, search, {},
                                                  settings.interrupt);
  return std::isfinite(found.value) ? std::min(own, found.value) : own;
}

double chi_square_ratio(double chi_square, int residual_terms, int parameters) {
  return std::sqrt(chi_square / std::max(1.0, static_cast<double>(residual_terms - parameters)));
}

double criterion(const FitResult& fit, int residual_terms, bool weighted, const NoiseEstimate& noise) {
  const double n = static_cast<double>(residual_terms);
  const double penalty = static_cast<double>(fit.free.size()) * std::log(n);
  if (weighted) return noise_chi_square(fit, noise) + penalty;
  return n * std::log(std::max(fit.objective, 1e-300)) + penalty;
}

}  // namespace rheo::runtime::diagnosis
