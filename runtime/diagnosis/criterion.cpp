#include "runtime/diagnosis/criterion.hpp"

#include "runtime/fit/data_set_fit.hpp"
#include "runtime/fit/fit_coordinates.hpp"
#include "runtime/fit/fit_scoring.hpp"
#include "runtime/fit/fit_search.hpp"
#include "runtime/fit/objective.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

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

// The variance of a damping term r_d at the measured phase PHASE under NOISE (criterion.hpp) at
// amplitude A, frequency F; 0 where eq. 5.1 leaves the term out (phase outside (0, pi)).
double damping_variance(double phase, const NoiseEstimate& noise, double a, double f) {
  if (!keeps_damping_term(phase)) return 0.0;
  const double s_phi2 = noise.phase * noise.phase * noise.phase_profile.factor(a, f), cot = std::cos(phase) / std::sin(phase);
  return s_phi2 * cot * cot + 0.5 * s_phi2 * s_phi2;
}

// The variance of a stiffness term r_K at amplitude A, frequency F.
double stiffness_variance(const NoiseEstimate& noise, double a, double f) {
  return noise.stiffness * noise.stiffness * noise.stiffness_profile.factor(a, f);
}

}  // namespace

double noise_chi_square(const FitResult& fit, const NoiseEstimate& noise) {
  const bool varies = noise.stiffness_profile.varies || noise.phase_profile.varies;
  double chi2 = 0.0;
  for (const auto& set : fit.datasets) {
    if (!set.harmonic) continue;
    for (std::size_t i = 0; i < set.residuals.stiffness.size(); ++i) {
      const double a = varies ? set.prediction.points.at(i).amplitude : 1.0, f = varies ? set.prediction.points.at(i).frequency : 1.0;
      chi2 += set.residuals.stiffness[i] * set.residuals.stiffness[i] / stiffness_variance(noise, a, f);
      if (const double v = damping_variance(set.measured_phase[i], noise, a, f); v > 0.0)
        chi2 += set.residuals.damping[i] * set.residuals.damping[i] / v;
    }
  }
  return chi2;
}

LeastChiSquare least_chi_square(const FitResult& fit, const std::vector<FitDataSet>& data, const NoiseEstimate& noise, const FitSettings& settings,
                                int evaluations) {
  const LeastChiSquare own{noise_chi_square(fit, noise), fit.network.parameters()};
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
        r.push_back((m.stiffness / d.stiffness[i] - 1.0) / std::sqrt(stiffness_variance(noise, d.amplitude[i], d.frequency[i])));
        const double v = damping_variance(d.phase[i], noise, d.amplitude[i], d.frequency[i]);
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
  if (!(std::isfinite(found.value) && found.value < own.chi_square)) return own;
  return {found.value, coordinates.values(found.z)};
}

FitResult fit_at(const FitResult& fit, const std::vector<double>& values, const std::vector<FitDataSet>& data, const HarmonicOptions& harmonic) {
  FitResult at = fit;
  at.network = fit.network.with_parameters(values);
  at.datasets.clear();
  for (const FitDataSet& set : data) at.datasets.push_back(data_set_fit(at.network, set, harmonic));
  return at;
}

NoiseAndChiSquare noise_at_likelihood_maximum(const FitResult& fit, const std::vector<FitDataSet>& data, const NoiseEstimate& noise,
                                              const FitSettings& settings, int evaluations) {
  NoiseAndChiSquare out{noise, 0.0, 0};
  const int terms = residual_terms(data), p = static_cast<int>(fit.free.size());
  FitResult at = fit;
  for (int round = 0; round < kNoiseRounds; ++round) {
    const LeastChiSquare least = least_chi_square(at, data, out.noise, settings, round == 0 ? evaluations : evaluations / 2);
    ++out.rounds;
    out.chi_square = least.chi_square;
    at = fit_at(at, least.values, data, settings.score.harmonic);
    at.start_values.clear();  // later rounds search from the last point alone
    const NoiseEstimate again = estimate_noise(at, data);
    if (!noise_weighted(data, again)) break;
    const double chi_square = std::min(noise_chi_square(at, again), noise_chi_square(fit, again));
    // Taken only where the residual it came from is at it: a fit weighted to a term whose noise
    // is near 0 follows that term, and its smoother residual would give a smaller noise still.
    if (beyond_noise_ratio(chi_square_ratio(chi_square, terms, p), again)) break;
    const double change = std::abs(std::log(again.stiffness / again.phase) - std::log(out.noise.stiffness / out.noise.phase));
    out.noise = again, out.chi_square = chi_square;
    if (change <= kNoiseRatioChange) break;
  }
  return out;
}

double residual_ratio(const Residual& residual, const NoiseEstimate& noise, int residual_terms, bool weighted) {
  if (weighted) return chi_square_ratio(residual.chi_square, residual_terms, residual.parameters);
  if (noise.estimated && !(noise.floor > 0.0)) return residual.gap > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
  return noise_ratio(residual.gap, noise, residual_terms, residual.parameters);
}

bool reaches_noise(const Residual& before, const Residual& after, const NoiseEstimate& noise, int residual_terms, bool weighted) {
  if (!noise.estimated) return false;
  return beyond_noise_ratio(residual_ratio(before, noise, residual_terms, weighted), noise) &&
         !beyond_noise_ratio(residual_ratio(after, noise, residual_terms, weighted), noise);
}

bool lowers_residual(const Residual& before, const Residual& after, double share, int residual_terms, bool weighted) {
  if (after.gap <= (1.0 - share) * before.gap) return true;
  return weighted && chi_square_ratio(after.chi_square, residual_terms, after.parameters) <=
                         (1.0 - share) * chi_square_ratio(before.chi_square, residual_terms, before.parameters);
}

double chi_square_ratio(double chi_square, int residual_terms, int parameters) {
  return std::sqrt(chi_square / std::max(1.0, static_cast<double>(residual_terms - parameters)));
}

int fitted_parameters(const FitResult& fit) {
  const auto offsets = std::count_if(fit.datasets.begin(), fit.datasets.end(), [](const DataSetFit& set) { return set.force_offset.free; });
  return static_cast<int>(fit.free.size()) + static_cast<int>(offsets);
}

namespace {

// RICHER below SIMPLER by more than EVIDENCE times the overdispersion of the richer fit (above).
bool lower_by(double richer, double simpler, int parameters, int residual_terms, double evidence) {
  const double chi_square = richer - parameters * std::log(static_cast<double>(residual_terms));
  const double overdispersion = residual_terms > parameters ? std::max(1.0, chi_square / (residual_terms - parameters)) : 1.0;
  return simpler - richer > evidence * overdispersion;
}

}  // namespace

bool decisively_lower(double richer, double simpler, int parameters, int residual_terms) {
  return lower_by(richer, simpler, parameters, residual_terms, kDecisiveCriterion);
}

bool positively_lower(double richer, double simpler, int parameters, int residual_terms) {
  return lower_by(richer, simpler, parameters, residual_terms, kPositiveCriterion);
}

double criterion(const FitResult& fit, int residual_terms, bool weighted, const NoiseEstimate& noise) {
  const double n = static_cast<double>(residual_terms);
  const double penalty = static_cast<double>(fitted_parameters(fit)) * std::log(n);
  if (weighted) return noise_chi_square(fit, noise) + penalty;
  return n * std::log(std::max(fit.objective, 1e-300)) + penalty;
}

}  // namespace rheo::runtime::diagnosis
