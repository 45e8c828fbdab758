#include "runtime/report/report_figures.hpp"

#include "runtime/core/errors.hpp"

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
  Plot plot{id,
            title,
            {along_frequency ? "frequency [Hz]" : "amplitude [mm]", scale_for(along)},
            {stiffness ? "dynamic stiffness [N/mm]" : "phase [deg]", Scale::linear},
            {}};
  const std::vector<double> picked = curve_keys(keys);
  for (std::size_t c = 0; c < picked.size(); ++c) {
    std::vector<std::size_t> members;
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (same(keys[i], picked[c])) members.push_back(i);
    std::sort(members.begin(), members.end(), [&](std::size_t a, std::size_t b) { return along[a] < along[b]; });
    const std::string group = fmt::format("{:g} {}", picked[c], along_frequency ? "mm" : "Hz");
    Series model{group + " model", group, static_cast<int>(c), SeriesStyle::line, {}, {}};
    Series measured{group + " measured", group, static_cast<int>(c), SeriesStyle::markers, {}, {}};
    Series baseline{group + " model before", group, static_cast<int>(c), SeriesStyle::dashed, {}, {}};
    for (const std::size_t i : members) {
      model.x.push_back(along[i]);
      model.y.push_back(scale * (stiffness ? g.model_stiffness : g.model_phase).at(i));
      if (g.has_baseline()) {
        baseline.x.push_back(along[i]);
        baseline.y.push_back(scale * (stiffness ? g.baseline_stiffness : g.baseline_phase).at(i));
      }
      if (!g.measured()) continue;
      measured.x.push_back(along[i]);
      measured.y.push_back(scale * (stiffness ? g.measured_stiffness : g.measured_phase).at(i));
    }
    if (g.measured()) plot.series.push_back(std::move(measured));
    if (g.has_baseline()) plot.series.push_back(std::move(baseline));
    plot.series.push_back(std::move(model));
  }
  if (g.has_baseline()) plot.meaning[1] = "refined", plot.meaning[2] = "before";  // short: the legend column is 138 units wide
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
  const auto map_pair = [&](const std::vector<double>& k, const std::vector<double>& phase, const std::string& whose) {
    std::vector<ResidualMap> maps{{"Stiffness residual K/K_exp - 1" + whose, "%", g.amplitude, g.frequency, {}, 0.0},
                                  {"Phase residual phase - phase_exp" + whose, "deg", g.amplitude, g.frequency, {}, 0.0}};
    for (std::size_t i = 0; i < g.amplitude.size(); ++i) {
      maps[0].value.push_back(100.0 * (k.at(i) / g.measured_stiffness.at(i) - 1.0));
      maps[1].value.push_back(kDegree * (phase.at(i) - g.measured_phase.at(i)));
    }
    return maps;
  };
  if (!g.has_baseline()) return map_pair(g.model_stiffness, g.model_phase, "");
  std::vector<ResidualMap> maps = map_pair(g.model_stiffness, g.model_phase, ", refined");
  for (ResidualMap& before : map_pair(g.baseline_stiffness, g.baseline_phase, ", before")) maps.push_back(std::move(before));
  for (std::size_t k = 0; k < 2; ++k) {  // before and after on one colour scale
    std::vector<double> both = maps[k].value;
    both.insert(both.end(), maps[k + 2].value.begin(), maps[k + 2].value.end());
    maps[k].limit = maps[k + 2].limit = color_scale_limit(both);
  }
  return maps;
}

Plot hysteresis_plot(const HistoryComparison& h, const std::string& id) {
  Plot plot{id, "Hysteresis: force over displacement", {"displacement [mm]", Scale::linear}, {"force [N]", Scale::linear}, {}};
  constexpr std::size_t kMarkers = 400, kLinePoints = 4000;
  // One group alone keeps the legend to a single "history" entry; with more, each is named.
  const bool alone = !h.measured() && !h.has_baseline();
  const std::string model = h.has_baseline() ? "model refined" : "model";
  if (h.measured())
    plot.series.push_back({"measured", "measured", 0, SeriesStyle::markers, every(h.displacement, kMarkers), every(h.measured_force, kMarkers)});
  if (h.has_baseline())
    plot.series.push_back(
        {"model before", "model before", 2, SeriesStyle::dashed, every(h.displacement, kLinePoints), every(h.baseline_force, kLinePoints)});
  plot.series.push_back(
      {model, alone ? "history" : model, 1, SeriesStyle::line, every(h.displacement, kLinePoints), every(h.model_force, kLinePoints)});
  return plot;
}

std::string primary_figure_svg(const ReportContent& content) {
  if (!content.harmonic.empty()) return render_svg(harmonic_plots(content.harmonic.front(), "plot").front(), true);
  if (!content.histories.empty()) return render_svg(hysteresis_plot(content.histories.front(), "plot"), true);
  throw UsageError("--plot: there is nothing to plot (no harmonic grid and no time history); give --data or a simulate protocol");
}

}  // namespace rheo::runtime::report
