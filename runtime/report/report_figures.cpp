#include "runtime/report/report_figures.hpp"

#include "runtime/errors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rheo::runtime::report {
namespace {

constexpr double kDegree = 180.0 / std::numbers::pi;

bool same(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b)); }

// The distinct values of `keys`, at most kMaxCurves of them spread evenly, increasing.
std::vector<double> curve_keys(std::vector<double> keys) {
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end(), same), keys.end());
  if (keys.size() <= kMaxCurves) return keys;
  std::vector<double> picked;
  for (std::size_t i = 0; i < kMaxCurves; ++i)
    picked.push_back(keys[static_cast<std::size_t>(std::lround(static_cast<double>(i) * static_cast<double>(keys.size() - 1) / (kMaxCurves - 1)))]);
  return picked;
}

// Stiffness or phase over frequency (a curve per amplitude) or over amplitude (a curve per frequency).
Plot curves(const HarmonicComparison& g, const std::string& id, const std::string& title, bool along_frequency, bool stiffness) {
  const std::vector<double>& along = along_frequency ? g.frequency : g.amplitude;
  const std::vector<double>& keys = along_frequency ? g.amplitude : g.frequency;
  const double scale = stiffness ? 1.0 : kDegree;
  Plot plot{id, title, {along_frequency ? "frequency [Hz]" : "amplitude [mm]", scale_for(along)},
            {stiffness ? "dynamic stiffness [N/mm]" : "phase [deg]", Scale::linear}, {}};
  const std::vector<double> picked = curve_keys(keys);
  for (std::size_t c = 0; c < picked.size(); ++c) {
    std::vector<std::size_t> members;
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (same(keys[i], picked[c])) members.push_back(i);
    std::sort(members.begin(), members.end(), [&](std::size_t a, std::size_t b) { return along[a] < along[b]; });
    const std::string group = fmt::format("{:g} {}", picked[c], along_frequency ? "mm" : "Hz");
    Series model{group + " model", group, static_cast<int>(c), SeriesStyle::line, {}, {}};
    Series measured{group + " measured", group, static_cast<int>(c), SeriesStyle::markers, {}, {}};
    for (const std::size_t i : members) {
      model.x.push_back(along[i]);
      model.y.push_back(scale * (stiffness ? g.model_stiffness : g.model_phase).at(i));
      if (!g.measured()) continue;
      measured.x.push_back(along[i]);
      measured.y.push_back(scale * (stiffness ? g.measured_stiffness : g.measured_phase).at(i));
    }
    if (g.measured()) plot.series.push_back(std::move(measured));
    plot.series.push_back(std::move(model));
  }
  return plot;
}

std::vector<double> every(const std::vector<double>& v, std::size_t limit) {
  const std::size_t stride = std::max<std::size_t>(1, (v.size() + limit - 1) / limit);
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); i += stride) out.push_back(v[i]);
  return out;
}

}  // namespace

std::vector<Plot> harmonic_plots(const HarmonicComparison& g, const std::string& prefix) {
  return {curves(g, prefix + "-stiffness-frequency", "Dynamic stiffness over frequency", true, true),
          curves(g, prefix + "-phase-frequency", "Phase over frequency", true, false),
          curves(g, prefix + "-stiffness-amplitude", "Dynamic stiffness over amplitude", false, true),
          curves(g, prefix + "-phase-amplitude", "Phase over amplitude", false, false)};
}

std::vector<ResidualMap> residual_maps(const HarmonicComparison& g) {
  if (!g.measured()) return {};
  ResidualMap stiffness{"Stiffness residual K/K_exp - 1", "%", g.amplitude, g.frequency, {}};
  ResidualMap phase{"Phase residual phase - phase_exp", "deg", g.amplitude, g.frequency, {}};
  for (std::size_t i = 0; i < g.amplitude.size(); ++i) {
    stiffness.value.push_back(100.0 * (g.model_stiffness.at(i) / g.measured_stiffness.at(i) - 1.0));
    phase.value.push_back(kDegree * (g.model_phase.at(i) - g.measured_phase.at(i)));
  }
  return {stiffness, phase};
}

Plot hysteresis_plot(const HistoryComparison& h, const std::string& id) {
  Plot plot{id, "Hysteresis: force over displacement", {"displacement [mm]", Scale::linear}, {"force [N]", Scale::linear}, {}};
  constexpr std::size_t kMarkers = 400, kLinePoints = 4000;
  if (h.measured())
    plot.series.push_back({"measured", "history", 0, SeriesStyle::markers, every(h.displacement, kMarkers), every(h.measured_force, kMarkers)});
  plot.series.push_back({"model", "history", 1, SeriesStyle::line, every(h.displacement, kLinePoints), every(h.model_force, kLinePoints)});
  if (h.measured()) plot.series.back().group = "model", plot.series.front().group = "measured";
  return plot;
}

std::string primary_figure_svg(const ReportContent& content) {
  if (!content.harmonic.empty()) return render_svg(harmonic_plots(content.harmonic.front(), "plot").front(), true);
  if (!content.histories.empty()) return render_svg(hysteresis_plot(content.histories.front(), "plot"), true);
  throw UsageError("--plot: there is nothing to plot (no harmonic grid and no time history); give --data or a simulate protocol");
}

}  // namespace rheo::runtime::report
