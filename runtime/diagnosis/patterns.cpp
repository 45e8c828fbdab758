#include "runtime/diagnosis/patterns.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace rheo::runtime::diagnosis {
namespace {

struct GridPoint {
  std::size_t amplitude = 0, frequency = 0;  // level indices
  double r_k = 0.0, r_d = 0.0;
};

// Index of VALUE among LEVELS (sorted), adding it when no level lies within 1e-9 relative.
std::size_t level_of(std::vector<double>& levels, double value) {
  for (std::size_t i = 0; i < levels.size(); ++i)
    if (std::abs(levels[i] - value) <= 1e-9 * std::max(std::abs(value), 1e-300)) return i;
  levels.push_back(value);
  return levels.size() - 1;
}

// Shares of the amplitude and frequency main effects and the interaction, on r_K and r_d alike.
void decompose(const std::vector<GridPoint>& grid, std::size_t n_a, std::size_t n_f, HarmonicPatterns& out) {
  double total = 0.0;
  for (const auto& g : grid) total += g.r_k * g.r_k + g.r_d * g.r_d;
  if (!(total > 0.0)) return;
  double ss_a = 0.0, ss_f = 0.0, ss_i = 0.0;
  for (int component = 0; component < 2; ++component) {
    auto r = [&](const GridPoint& g) { return component == 0 ? g.r_k : g.r_d; };
    double mean = 0.0;
    for (const auto& g : grid) mean += r(g);
    mean /= static_cast<double>(grid.size());
    std::vector<double> a(n_a, 0.0), f(n_f, 0.0);
    for (int sweep = 0; sweep < 50; ++sweep) {  // back-fitting: exact in one sweep on a full grid
      std::vector<double> sum(a.size(), 0.0), count(a.size(), 0.0);
      for (const auto& g : grid) sum[g.amplitude] += r(g) - mean - f[g.frequency], count[g.amplitude] += 1.0;
      for (std::size_t i = 0; i < a.size(); ++i) a[i] = count[i] > 0 ? sum[i] / count[i] : 0.0;
      std::vector<double> fsum(f.size(), 0.0), fcount(f.size(), 0.0);
      for (const auto& g : grid) fsum[g.frequency] += r(g) - mean - a[g.amplitude], fcount[g.frequency] += 1.0;
      for (std::size_t i = 0; i < f.size(); ++i) f[i] = fcount[i] > 0 ? fsum[i] / fcount[i] : 0.0;
    }
    for (const auto& g : grid) {
      const double interaction = r(g) - mean - a[g.amplitude] - f[g.frequency];
      ss_a += a[g.amplitude] * a[g.amplitude];
      ss_f += f[g.frequency] * f[g.frequency];
      ss_i += interaction * interaction;
    }
  }
  out.amplitude_share = ss_a / total;
  out.frequency_share = ss_f / total;
  out.interaction_share = ss_i / total;
}

// C - (n_a + n_f - components) for the distinct cells of GRID (see patterns.hpp).
int interaction_dof(const std::vector<GridPoint>& grid, std::size_t n_a, std::size_t n_f) {
  std::vector<std::size_t> parent(n_a + n_f);
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = i;
  auto find = [&](std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  std::vector<std::pair<std::size_t, std::size_t>> cells;
  for (const auto& g : grid) cells.emplace_back(g.amplitude, g.frequency);
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  std::size_t components = n_a + n_f;
  for (const auto& [a, f] : cells)
    if (const std::size_t ra = find(a), rf = find(n_a + f); ra != rf) parent[ra] = rf, --components;
  return static_cast<int>(cells.size()) - static_cast<int>(n_a + n_f - components);
}

}  // namespace

ResidualPatterns residual_patterns(const FitResult& fit, const std::vector<FitDataSet>& data) {
  ResidualPatterns out;
  std::vector<double> amplitudes, frequencies;
  std::vector<GridPoint> grid;
  std::map<std::size_t, std::pair<double, int>> phase_excess;  // frequency level -> (sum of excess, count)
  HarmonicPatterns& h = out.harmonic;
  double sum_k = 0.0, sum_phase = 0.0;
  for (std::size_t s = 0; s < data.size(); ++s) {
    const DataSetFit& set_fit = fit.datasets[s];
    if (!data[s].is_harmonic()) {
      const HistoryData& d = data[s].history();
      HistoryPatterns p{d.path, set_fit.err, set_fit.worst};
      double largest = -1.0;
      for (std::size_t j = 0; j < d.force.size(); ++j)
        if (const double e = std::abs(set_fit.prediction.force[j] - d.force[j]); e > largest)
          largest = e, p.worst_displacement = d.drive.displacement[j];
      out.histories.push_back(p);
      continue;
    }
    out.has_harmonic = true;
    const HarmonicData& d = data[s].harmonic();
    for (std::size_t j = 0; j < d.size(); ++j) {
      GridPoint g{level_of(amplitudes, d.amplitude[j]), level_of(frequencies, d.frequency[j]), set_fit.residuals.stiffness[j],
                  set_fit.residuals.damping[j]};
      grid.push_back(g);
      const double phase_error = set_fit.prediction.points[j].measures.phase - d.phase[j];
      sum_k += g.r_k * g.r_k;
      sum_phase += phase_error * phase_error;
      auto& [excess, count] = phase_excess[g.frequency];
      excess += -phase_error, count += 1;
      if (std::abs(g.r_k) > std::abs(h.worst_stiffness.residual)) h.worst_stiffness = {d.amplitude[j], d.frequency[j], g.r_k};
      if (std::abs(phase_error) > std::abs(h.worst_phase.residual)) h.worst_phase = {d.amplitude[j], d.frequency[j], phase_error};
    }
  }
  if (!out.has_harmonic) return out;
  h.points = static_cast<int>(grid.size());
  h.stiffness_rms = std::sqrt(sum_k / h.points);
  h.phase_rms = std::sqrt(sum_phase / h.points);
  decompose(grid, amplitudes.size(), frequencies.size(), h);
  h.interaction_dof = interaction_dof(grid, amplitudes.size(), frequencies.size());
  h.phase_peak = -1e300;
  for (const auto& [level, entry] : phase_excess)
    if (const double mean = entry.first / entry.second; mean > h.phase_peak) h.phase_peak = mean, h.phase_peak_frequency = frequencies[level];
  return out;
}

}  // namespace rheo::runtime::diagnosis
