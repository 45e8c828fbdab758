#include "runtime/diagnosis/global_look.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/fit/fit_scoring.hpp"
#include "lang/units.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace rheo::runtime::diagnosis {
namespace {

// The smallest and largest measured force amplitude [N].
std::pair<double, double> force_range(const std::vector<FitDataSet>& data) {
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (const auto& set : data) {
    if (set.is_harmonic()) {
      const HarmonicData& h = set.harmonic();
      for (std::size_t j = 0; j < h.size(); ++j)
        if (const double f = h.stiffness[j] * h.amplitude[j]; f > 0.0) lo = std::min(lo, f), hi = std::max(hi, f);
      continue;
    }
    const double f = set.history().force_scale;
    if (f > 0.0) lo = std::min(lo, f / 100.0), hi = std::max(hi, f);
  }
  return hi > 0.0 ? std::pair{lo, hi} : std::pair{1.0, 1.0};
}

double radical_inverse(unsigned long index, unsigned base) {
  double result = 0.0, fraction = 1.0 / base;
  for (; index > 0; index /= base, fraction /= base) result += fraction * static_cast<double>(index % base);
  return result;
}

double objective_at(const Network& network, const std::vector<FitDataSet>& data, const ScoreSettings& score) {
  std::vector<double> r;
  try {
    for (const auto& set : data)
      append_residuals(set, predict(network, set, FitMethod::exact, score.harmonic, nullptr, Offsets::applied), score, r);
  } catch (const NumericalError&) {
    return std::numeric_limits<double>::infinity();
  }
  double sum = 0.0;
  for (double v : r) sum += v * v;
  return std::isfinite(sum) ? sum : std::numeric_limits<double>::infinity();
}

// A position (a gap's centre): a length whose bounds hold zero inside. Its start, the screen's
// (centred play, or play off-centre by half its half width), may sit where the objective cannot
// tell it from its mirror image: on harmonic data about zero, play at -c scores as play at +c,
// so at c = 0 the gradient vanishes and a local search never leaves the centre.
bool is_position(const lang::Parameter& p) { return p.dimension == lang::dim::length && p.lower < 0.0 && p.upper > 0.0; }

}  // namespace

std::pair<double, double> supported_range(const Network& network, int index, const std::vector<FitDataSet>& data, const DataScales& s) {
  const lang::Parameter& p = network.model().parameters.at(static_cast<std::size_t>(index));
  const double start = network.parameter(index), two_pi = 2.0 * std::numbers::pi;
  std::pair<double, double> range{start / 10.0, start * 10.0};
  const double k_lo = s.bounds.stiffness / 300.0, k_hi = 3.0 * s.bounds.stiffness;
  const double w_lo = two_pi * s.frequency_low, w_hi = two_pi * s.frequency_high;
  const double tau_lo = 1.0 / w_hi / 3.0, tau_hi = 3.0 / w_lo;
  if (p.dimension == lang::dim::force) {
    const auto [lo, hi] = force_range(data);
    range = {lo / 10.0, hi};
  } else if (p.dimension == lang::dim::time) {
    range = {tau_lo, tau_hi};
  } else if (p.dimension == lang::dim::length) {
    range = {s.amplitude_low / 30.0, s.amplitude_high};
  } else if (p.dimension == lang::dim::stiffness) {
    range = {k_lo, k_hi};
  } else if (p.dimension == lang::dim::mass) {
    range = {k_lo / (w_hi * w_hi), k_hi / (w_lo * w_lo)};
  } else if (p.dimension == lang::dim::damping) {
    range = {k_lo * tau_lo, k_hi * tau_hi};
  }
  return {std::clamp(range.first, p.lower, p.upper), std::clamp(range.second, p.lower, p.upper)};
}

std::vector<SampledStart> global_look(const Network& start, const std::vector<int>& added, const std::vector<FitDataSet>& data,
                                      const ScoreSettings& score, int samples, int starts) {
  const DataScales scales = data_scales(data);
  std::vector<int> sampled;
  std::vector<std::pair<double, double>> box;  // ln of the supported range; a position's bounds themselves
  std::vector<bool> linear;                    // a position: sampled uniformly
  for (int i : added) {
    const lang::Parameter& p = start.model().parameters.at(static_cast<std::size_t>(i));
    if (is_position(p)) {
      sampled.push_back(i), box.emplace_back(p.lower, p.upper), linear.push_back(true);
      continue;
    }
    if (!(p.lower > 0.0)) continue;
    const auto [lo, hi] = supported_range(start, i, data, scales);
    sampled.push_back(i);
    box.emplace_back(std::log(lo), std::log(hi));
    linear.push_back(false);
  }
  std::vector<SampledStart> points{{start.parameters(), objective_at(start, data, score)}};
  static constexpr unsigned kPrimes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37};
  for (int k = 1; k <= samples && !sampled.empty(); ++k) {
    std::vector<double> values = start.parameters();
    for (std::size_t j = 0; j < sampled.size(); ++j) {
      const double t = radical_inverse(static_cast<unsigned long>(k), kPrimes[j % std::size(kPrimes)]);
      const double x = box[j].first + t * (box[j].second - box[j].first);
      values[static_cast<std::size_t>(sampled[j])] = linear[j] ? x : std::exp(x);
    }
    const Network network = start.with_parameters(values);
    points.push_back({values, objective_at(network, data, score)});
  }
  // The start (the screened element) always first; then the best samples.
  std::stable_sort(points.begin() + 1, points.end(), [](const SampledStart& a, const SampledStart& b) { return a.objective < b.objective; });
  points.resize(std::min(points.size(), static_cast<std::size_t>(std::max(1, starts))));
  return points;
}

}  // namespace rheo::runtime::diagnosis
