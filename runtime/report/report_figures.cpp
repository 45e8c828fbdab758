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

// A variable of the horizontal axis, or of the curves' keys: "frequency [Hz]", unit "Hz".
struct Variable {
  std::string label, unit;
  std::vector<double> values;
};

// One measure at every point: measured (empty without), model, baseline (empty without).
struct Measure {
  std::string label;  // of the vertical axis, with its unit
  std::vector<double> measured, model, baseline;
  bool log_allowed = true;  // false for the phase, which can be <= 0
};

// MEASURE at every point from stiffness K [N/mm] and phase [rad].
template <typename F>
Measure measure_of(const HarmonicComparison& g, std::string label, F of) {
  Measure m{std::move(label), {}, {}, {}, true};
  const auto fill = [&](const std::vector<double>& k, const std::vector<double>& phase, std::vector<double>& out) {
    for (std::size_t i = 0; i < k.size() && i < phase.size(); ++i) out.push_back(of(k[i], phase[i]));
  };
  fill(g.measured_stiffness, g.measured_phase, m.measured);
  fill(g.model_stiffness, g.model_phase, m.model);
  fill(g.baseline_stiffness, g.baseline_phase, m.baseline);
  return m;
}

// MEASURE over ALONG, a curve per value of KEY (at most kMaxCurves, curve_keys).
Plot curves(const HarmonicComparison& g, const std::string& id, const std::string& title, const Variable& along, const Variable& key,
            const Measure& y) {
  Plot plot{id, title, {along.label, scale_for(along.values)}, {y.label, Scale::linear}, {}};
  // Measured values decide the scale when there are some: a model far off them does not.
  std::vector<double> shown = y.measured;
  if (shown.empty()) shown = y.model, shown.insert(shown.end(), y.baseline.begin(), y.baseline.end());
  if (y.log_allowed) plot.y.scale = scale_for(shown);
  const std::vector<double> picked = curve_keys(key.values);
  for (std::size_t c = 0; c < picked.size(); ++c) {
    std::vector<std::size_t> members;
    for (std::size_t i = 0; i < key.values.size(); ++i)
      if (same(key.values[i], picked[c])) members.push_back(i);
    std::sort(members.begin(), members.end(), [&](std::size_t a, std::size_t b) { return along.values[a] < along.values[b]; });
    const std::string group = fmt::format("{:g} {}", picked[c], key.unit);
    Series model{group + " model", group, static_cast<int>(c), SeriesStyle::line, {}, {}};
    Series measured{group + " measured", group, static_cast<int>(c), SeriesStyle::markers, {}, {}};
    Series baseline{group + " model before", group, static_cast<int>(c), SeriesStyle::dashed, {}, {}};
    for (const std::size_t i : members) {
      model.x.push_back(along.values[i]);
      model.y.push_back(y.model.at(i));
      if (g.has_baseline()) {
        baseline.x.push_back(along.values[i]);
        baseline.y.push_back(y.baseline.at(i));
      }
      if (!g.measured()) continue;
      measured.x.push_back(along.values[i]);
      measured.y.push_back(y.measured.at(i));
    }
    if (g.measured()) plot.series.push_back(std::move(measured));
    if (g.has_baseline()) plot.series.push_back(std::move(baseline));
    plot.series.push_back(std::move(model));
  }
  if (g.has_baseline()) plot.meaning[1] = "refined", plot.meaning[2] = "before";  // short: the legend column is 138 units wide
  return plot;
}

std::size_t distinct_count(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return static_cast<std::size_t>(std::unique(v.begin(), v.end(), same) - v.begin());
}

std::vector<double> every(const std::vector<double>& v, std::size_t limit) {
  const std::size_t stride = std::max<std::size_t>(1, (v.size() + limit - 1) / limit);
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); i += stride) out.push_back(v[i]);
  return out;
}

}  // namespace

HarmonicAxes harmonic_axes(const HarmonicComparison& g) {
  const bool frequency_varies = distinct_count(g.frequency) > 1, amplitude_varies = distinct_count(g.amplitude) > 1;
  return {frequency_varies || !amplitude_varies, amplitude_varies};
}

std::vector<Plot> harmonic_plots(const HarmonicComparison& g, const std::string& prefix) {
  const Variable frequency{"frequency [Hz]", "Hz", g.frequency}, amplitude{"amplitude [mm]", "mm", g.amplitude};
  const Measure stiffness = measure_of(g, "dynamic stiffness [N/mm]", [](double k, double) { return k; });
  Measure phase = measure_of(g, "phase [deg]", [](double, double p) { return kDegree * p; });
  phase.log_allowed = false;
  const HarmonicAxes axes = harmonic_axes(g);
  std::vector<Plot> plots;
  if (axes.over_frequency) {
    plots.push_back(curves(g, prefix + "-stiffness-frequency", "Dynamic stiffness over frequency", frequency, amplitude, stiffness));
    plots.push_back(curves(g, prefix + "-phase-frequency", "Phase over frequency", frequency, amplitude, phase));
  }
  if (axes.over_amplitude) {
    plots.push_back(curves(g, prefix + "-stiffness-amplitude", "Dynamic stiffness over amplitude", amplitude, frequency, stiffness));
    plots.push_back(curves(g, prefix + "-phase-amplitude", "Phase over amplitude", amplitude, frequency, phase));
  }
  // Storage and loss over the first variable drawn; material data as moduli (N/mm^2 = MPa) over strain.
  const bool material = g.material();
  const double to_modulus = material ? *g.source.height / *g.source.area : 1.0;
  Variable strain{"strain [%]", "%", g.amplitude};
  for (double& v : strain.values) v *= 100.0 / g.source.height.value_or(1.0);
  const Variable& swept = material ? strain : amplitude;
  const Variable& along = axes.over_frequency ? frequency : swept;
  const Variable& key = axes.over_frequency ? swept : frequency;
  const Measure storage = measure_of(g, material ? "storage modulus E' = K'h/A [MPa]" : "storage stiffness K' [N/mm]",
                                     [&](double k, double p) { return to_modulus * k * std::cos(p); });
  const Measure loss = measure_of(g, material ? "loss modulus E'' = K''h/A [MPa]" : "loss stiffness K'' [N/mm]",
                                  [&](double k, double p) { return to_modulus * k * std::sin(p); });
  const char* over = axes.over_frequency ? "frequency" : "amplitude";
  const char* over_text = axes.over_frequency ? "frequency" : material ? "strain" : "amplitude";
  plots.push_back(curves(g, fmt::format("{}-storage-{}", prefix, over),
                         fmt::format("Storage {} over {}", material ? "modulus E'" : "stiffness K' = K cos(phase)", over_text), along, key, storage));
  plots.push_back(curves(g, fmt::format("{}-loss-{}", prefix, over),
                         fmt::format("Loss {} over {}", material ? "modulus E''" : "stiffness K'' = K sin(phase)", over_text), along, key, loss));
  return plots;
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
