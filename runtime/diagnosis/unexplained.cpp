#include "runtime/diagnosis/unexplained.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace rheo::runtime::diagnosis {
namespace {

// The narrowest run of adjacent levels of SUMS (level -> squared residual, sorted) holding at
// least half of the total; of equal widths, the one holding more.
std::optional<LevelRange> narrowest_half(const std::map<double, double>& sums) {
  std::vector<std::pair<double, double>> levels(sums.begin(), sums.end());
  double total = 0.0;
  for (const auto& [level, sum] : levels) total += sum;
  if (levels.empty() || !(total > 0.0)) return std::nullopt;
  std::optional<LevelRange> best;
  for (std::size_t i = 0; i < levels.size(); ++i) {
    double held = 0.0;
    for (std::size_t j = i; j < levels.size(); ++j) {
      held += levels[j].second;
      if (held < 0.5 * total) continue;
      const int width = static_cast<int>(j - i + 1);
      if (!best || width < best->levels || (width == best->levels && held / total > best->share))
        best = LevelRange{levels[i].first, levels[j].first, held / total, width, static_cast<int>(levels.size())};
      break;
    }
  }
  return best;
}

}  // namespace

ResidualShape residual_shape(const FitResult& fit, const std::vector<FitDataSet>& data) {
  ResidualShape out;
  std::map<double, double> by_amplitude, by_frequency;
  // Histories: r.s and s.s per signal, r.r.
  std::array<double, 6> rs{}, ss{};
  double rr = 0.0;
  for (std::size_t s = 0; s < data.size(); ++s) {
    const DataSetFit& set = fit.datasets[s];
    if (data[s].is_harmonic()) {
      const HarmonicData& d = data[s].harmonic();
      for (std::size_t j = 0; j < d.size(); ++j) {
        const double r2 = set.residuals.stiffness[j] * set.residuals.stiffness[j] + set.residuals.damping[j] * set.residuals.damping[j];
        by_amplitude[d.amplitude[j]] += r2;
        by_frequency[d.frequency[j]] += r2;
      }
      continue;
    }
    const HistoryData& h = data[s].history();
    const std::vector<double>& u = h.drive.displacement;
    const std::vector<double>& t = h.drive.time;
    for (std::size_t j = 0; j < h.force.size(); ++j) {
      const double r = (set.prediction.force[j] - h.force[j]) / h.force_scale;
      const std::size_t a = j == 0 ? 0 : j - 1, b = std::min(j + 1, u.size() - 1);
      const double v = t[b] > t[a] ? (u[b] - u[a]) / (t[b] - t[a]) : 0.0;
      const std::array<double, 6> signal{1.0, u[j] * u[j], u[j], u[j] * u[j] * u[j], v > 0.0 ? 1.0 : v < 0.0 ? -1.0 : 0.0, v};
      for (std::size_t k = 0; k < signal.size(); ++k) rs[k] += r * signal[k], ss[k] += signal[k] * signal[k];
      rr += r * r;
    }
  }
  out.amplitudes = narrowest_half(by_amplitude);
  out.frequencies = narrowest_half(by_frequency);
  if (rr > 0.0)
    for (std::size_t k = 0; k < rs.size(); ++k)
      if (ss[k] > 0.0)
        if (const double share = rs[k] * rs[k] / (ss[k] * rr); share > out.resembles_share)
          out.resembles_share = share, out.resembles = static_cast<Resemblance>(k);
  return out;
}

}  // namespace rheo::runtime::diagnosis
