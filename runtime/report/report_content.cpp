#include "runtime/report/report_content.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/fit/objective.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rheo::runtime::report {
namespace {

ParameterRow row_of(const lang::Parameter& p, double value) {
  ParameterRow row{p.path, written_unit(p), in_written_unit(p, value), std::nullopt, "", "", false};
  if (p.free) row.bounds = fmt::format("[{:g}, {:g}]", in_written_unit(p, p.lower), in_written_unit(p, p.upper));
  return row;
}

std::string standard_error_of(const FitResult& r, std::size_t j, const lang::Parameter& p, double value) {
  const ParameterStatistics& s = r.statistics;
  if (j < s.identifiable.size() && !s.identifiable[j]) return "not identifiable";
  if (j >= s.standard_error.size() || !std::isfinite(s.standard_error[j])) return "-";
  const double se = s.standard_error[j];
  return fmt::format("{:.3g} ({:.2g} %)", in_written_unit(p, se), value != 0.0 ? 100.0 * se / std::abs(value) : 0.0);
}

}  // namespace

ReportContent report_for_model(const Network& network, const std::string& source, const std::string& origin) {
  ReportContent content;
  const lang::CheckedModel& model = network.model();
  content.title = fmt::format("{}: model {}", origin, model.name);
  content.model = model.name;
  content.source = source;
  content.origin = origin;
  content.network = model.root;
  for (std::size_t i = 0; i < model.parameters.size(); ++i)
    content.parameters.push_back(row_of(model.parameters[i], network.parameter(static_cast<int>(i))));
  return content;
}

ReportContent report_from_fit(const FitResult& r, const std::vector<FitDataSet>& data, const FitDescription& d) {
  ReportContent content = report_for_model(r.network, d.source, "rheo fit");
  content.origin = fmt::format("rheo fit, method {}, objective {}, optimizer {}, seed {}", d.method, d.objective, d.optimizer, d.seed);
  const auto& parameters = r.network.model().parameters;
  for (std::size_t j = 0; j < r.free.size(); ++j) {
    const auto i = static_cast<std::size_t>(r.free[j]);
    ParameterRow& row = content.parameters.at(i);
    row.free = true;
    row.start = in_written_unit(parameters[i], r.start_values.at(i));
    row.standard_error = standard_error_of(r, j, parameters[i], r.network.parameter(r.free[j]));
  }
  for (std::size_t k = 0; k < data.size() && k < r.datasets.size(); ++k) {
    if (data[k].is_harmonic()) content.harmonic.push_back(compare_harmonic(data[k].harmonic(), r.datasets[k].prediction.points, data[k].source));
    else {
      // The offset as fitted: a refined model may fit one its data line does not state (rheo diagnose, effect offset).
      HistoryComparison& h = content.histories.emplace_back(compare_history(data[k], r.datasets[k].prediction));
      const FittedOffset& fitted = r.datasets[k].force_offset;
      h.offset = ForceOffset{.given = fitted.given, .free = fitted.free, .value = fitted.value};
    }
  }
  if (content.harmonic.size() > 1) content.notes.push_back(fmt::format("all harmonic data: phi (5.1) = {:.6g}, err (6.1) = {:.4e}", r.phi, r.err));
  content.notes.push_back(fmt::format("{} evaluations in {:.2f} s; {}", r.evaluations, r.wall_seconds,
                                      r.interrupted ? "interrupted: the best values found so far" : "optimizer status " + r.status));
  for (const std::string& note : r.notes) content.notes.push_back(note);
  for (std::string& note : bound_notes(r)) content.notes.push_back(std::move(note));
  return content;
}

HarmonicComparison compare_harmonic(const HarmonicData& data, const std::vector<HarmonicPoint>& model, const DataSource& source) {
  HarmonicComparison h{data.path, data.amplitude, data.frequency, {}, {}, data.stiffness, data.phase, 0.0, 0.0, {}, {}, 0.0, source};
  for (const HarmonicPoint& p : model) {
    h.model_stiffness.push_back(p.measures.stiffness);
    h.model_phase.push_back(p.measures.phase);
  }
  const RelativeResiduals r = relative_residuals(data, model);
  h.phi = phi(r, 1.0, 1.0);
  h.err = thesis_err(r);
  return h;
}

HistoryComparison compare_history(const HistoryData& data, const std::vector<double>& model_force, const DataSource& source) {
  HistoryComparison h{data.path, data.drive.displacement, model_force, data.force, 0.0, 0.0, {}, 0.0, source};
  double sum = 0.0;
  for (std::size_t j = 0; j < data.force.size() && j < model_force.size(); ++j) {
    const double r = (model_force[j] - data.force[j]) / data.force_scale;
    sum += r * r;
    h.worst = std::max(h.worst, std::abs(r));
  }
  h.rms = data.force.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(data.force.size()));
  return h;
}

HistoryComparison compare_history(const FitDataSet& set, const Prediction& prediction) {
  HistoryComparison h = compare_history(set.history(), prediction.force, set.source);
  h.offset = set.force_offset;
  h.offset_value = prediction.force_offset;
  return h;
}

void add_baseline(ReportContent& content, const FitResult& earlier, const std::string& what) {
  std::size_t harmonic = 0, history = 0;
  for (const DataSetFit& set : earlier.datasets) {
    if (set.harmonic) {
      HarmonicComparison& h = content.harmonic.at(harmonic++);
      if (set.prediction.points.size() != h.amplitude.size())
        throw std::logic_error("add_baseline: the earlier fit's grid differs from the report's");
      for (const HarmonicPoint& p : set.prediction.points) {
        h.baseline_stiffness.push_back(p.measures.stiffness);
        h.baseline_phase.push_back(p.measures.phase);
      }
      h.baseline_err = set.err;
    } else {
      HistoryComparison& h = content.histories.at(history++);
      h.baseline_force = set.prediction.force;
      h.baseline_rms = set.err;
    }
  }
  content.baseline = what;
}

void add_simulation_result(ReportContent& content, const std::string& label, const ProtocolResult& result) {
  if (const auto* grid = std::get_if<HarmonicGrid>(&result.data)) {
    HarmonicComparison h{label, {}, {}, {}, {}, {}, {}, 0.0, 0.0, {}, {}, 0.0};
    for (const HarmonicPoint& p : grid->points) {
      h.amplitude.push_back(p.amplitude);
      h.frequency.push_back(p.frequency);
      h.model_stiffness.push_back(p.measures.stiffness);
      h.model_phase.push_back(p.measures.phase);
    }
    content.harmonic.push_back(std::move(h));
  } else {
    const History& history = std::get<History>(result.data);
    content.histories.push_back({label, history.displacement, history.force, {}, 0.0, 0.0, {}, 0.0});
  }
}

}  // namespace rheo::runtime::report
