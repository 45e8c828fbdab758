#include "runtime/fit/fit_report.hpp"

#include "runtime/fit/parameter_bounds.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

namespace rheo::runtime {
namespace {

double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }

const lang::Parameter& parameter_of(const FitResult& r, int index) { return r.network.model().parameters.at(static_cast<std::size_t>(index)); }

std::string data_kind(const DataSetFit& d) { return d.harmonic ? "harmonic" : "history"; }

std::size_t data_points(const DataSetFit& d) { return d.harmonic ? d.prediction.points.size() : d.prediction.force.size(); }

std::string standard_error_text(const FitResult& r, std::size_t j, int index) {
  const auto& s = r.statistics;
  if (j >= s.standard_error.size()) return "-";
  if (j < s.identifiable.size() && !s.identifiable[j]) return "not identifiable";
  const double value = r.network.parameter(index);
  const double se = s.standard_error[j];
  if (!std::isfinite(se)) return "-";
  return fmt::format("{:.3g} ({:.2g} %)", in_written_unit(parameter_of(r, index), se), value != 0.0 ? 100.0 * se / std::abs(value) : 0.0);
}

// "data rig.csv: force_offset": the parameter table's name of a fitted offset.
// The element of MODEL whose stiffness (slot 0 of a spring, maxwell or friction element) is
// parameter INDEX, with the block holding it; {nullptr, nullptr} otherwise.
std::pair<const lang::Element*, const lang::Element*> stiffness_owner(const lang::Element& block, int index) {
  for (const lang::Element& e : block.children) {
    const bool stiffness = (e.kind == lang::ElementKind::spring || e.kind == lang::ElementKind::maxwell || e.kind == lang::ElementKind::friction) &&
                           !e.parameters.empty() && e.parameters.front() == index;
    if (stiffness) return {&e, &block};
    if (auto found = stiffness_owner(e, index); found.first != nullptr) return found;
  }
  return {nullptr, nullptr};
}

// Why the parameters of GROUP (indices into r.free) are not identifiable: they act only
// together, spanning UNDETERMINED directions the data leave free; for stiffnesses in one series
// chain, the combination the data fix.
std::string together_note(const FitResult& r, const std::vector<int>& group, int undetermined) {
  std::vector<std::string> paths, names;
  const lang::Element* chain = nullptr;
  bool series = true;
  for (int j : group) {
    const int index = r.free.at(static_cast<std::size_t>(j));
    paths.push_back(parameter_of(r, index).path);
    const auto [element, block] = stiffness_owner(r.network.model().root, index);
    series = series && element != nullptr && block->kind == lang::ElementKind::series && (chain == nullptr || chain == block);
    if (element != nullptr) chain = block, names.push_back(element->name);
  }
  const int size = static_cast<int>(group.size()), determined = size - undetermined;
  if (determined <= 0)
    return fmt::format("  not identifiable: {} act only together; the data determine none of their combinations: fix them\n",
                       fmt::join(paths, " and "));
  std::string out = determined == 1 ? fmt::format("  not identifiable: {} act only together; the data determine one combination of them",
                                                  fmt::join(paths, " and "))
                                    : fmt::format("  not identifiable: {} act only together; the data determine {} combinations of them",
                                                  fmt::join(paths, " and "), determined);
  if (determined == 1 && series && size == 2) out += fmt::format(" (in series: only {0} {1}/({0} + {1}))", names[0], names[1]);
  else if (determined == 1 && series) out += fmt::format(" (in series: only 1/(1/{}))", fmt::join(names, " + 1/"));
  return out + (determined == 1 ? ": fix all but one of them\n" : fmt::format(": fix {} of them\n", undetermined));
}

std::string offset_label(const DataSetFit& d) { return fmt::format("data {}: force_offset", d.path); }

bool fitted_offset(const DataSetFit& d) { return !d.harmonic && d.force_offset.given && d.force_offset.free; }

std::string offset_error_text(const FittedOffset& o) {
  if (!o.identifiable) return "not identifiable";
  return std::isfinite(o.standard_error) ? fmt::format("{:.3g}", o.standard_error) : "-";
}

// ", force offset 120 N": a declared offset on the data set's line of the report.
std::string declared_offset_text(const DataSetFit& d) {
  if (d.harmonic || !d.force_offset.given) return "";
  return d.force_offset.free ? ", force offset fitted" : fmt::format(", force offset {:g} N", d.force_offset.value);
}

}  // namespace

std::string source_text(const DataSource& s) {
  std::string out;
  if (!s.step.empty()) out += fmt::format("; TRIOS step \"{}\"", s.step);
  if (s.material)
    out += fmt::format("; material data: stiffness = modulus x {:g} mm^2 / {:g} mm, amplitude = strain x {:g} mm", s.area.value_or(0.0),
                       s.height.value_or(0.0), s.height.value_or(0.0));
  return out;
}

std::string written_unit(const lang::Parameter& p) { return p.unit.empty() ? lang::internal_unit(p.dimension) : p.unit; }

double in_written_unit(const lang::Parameter& p, double internal_value) {
  if (p.unit.empty()) return internal_value;
  const auto unit = lang::parse_unit(p.unit);
  return unit ? internal_value / unit->scale : internal_value;
}

std::vector<std::string> bound_notes(const FitResult& r) {
  std::vector<std::string> out;
  for (int i : r.free) {
    const lang::Parameter& p = parameter_of(r, i);
    const BoundSide side = bound_reached(p, r.network.parameter(i));
    if (side == BoundSide::none) continue;
    const double bound = side == BoundSide::lower ? p.lower : p.upper;
    out.push_back(fmt::format("{} = {:.6g} {} is at its {} bound {:g}: widen it?", p.path, in_written_unit(p, r.network.parameter(i)),
                              written_unit(p), side == BoundSide::lower ? "lower" : "upper", in_written_unit(p, bound)));
  }
  return out;
}

std::string fit_report_text(const FitDescription& d, const FitResult& r) {
  std::string out = fmt::format("rheo fit: model {} from {}\n", r.network.model().name, d.source);
  for (const DataSetFit& set : r.datasets)
    out += fmt::format("  data {} ({}, {} {}, weight {:g}{}{})\n", set.path, data_kind(set), data_points(set), set.harmonic ? "points" : "samples",
                       set.weight, declared_offset_text(set), source_text(set.source));
  out += fmt::format("  method {}, objective {}, optimizer {}, seed {}\n", d.method, d.objective, d.optimizer, d.seed);
  for (const std::string& note : r.notes) out += fmt::format("  {}\n", note);
  out += "\n";
  std::size_t width = 9;
  for (int i : r.free) width = std::max(width, parameter_of(r, i).path.size());
  for (const DataSetFit& set : r.datasets)
    if (fitted_offset(set)) width = std::max(width, offset_label(set).size());
  out += fmt::format("  {:<{}}  {:>12}  {:>12}  {:<22}  {:<8}  {}\n", "parameter", width, "start", "fitted", "std. error", "unit", "bounds");
  for (std::size_t j = 0; j < r.free.size(); ++j) {
    const int i = r.free[j];
    const lang::Parameter& p = parameter_of(r, i);
    const double start = r.start_values.at(static_cast<std::size_t>(i));
    const bool at_bound = bound_reached(p, r.network.parameter(i)) != BoundSide::none;
    const bool yeoh_started = std::find(r.yeoh_started.begin(), r.yeoh_started.end(), i) != r.yeoh_started.end();
    out += fmt::format("  {:<{}}  {:>12.6g}  {:>12.6g}  {:<22}  {:<8}  [{:g}, {:g}]{}{}\n", p.path, width, in_written_unit(p, start),
                       in_written_unit(p, r.network.parameter(i)), standard_error_text(r, j, i), written_unit(p), in_written_unit(p, p.lower),
                       in_written_unit(p, p.upper), yeoh_started ? "  start: yeoh mean curve" : "", at_bound ? "  at a bound: widen it?" : "");
  }
  for (const DataSetFit& set : r.datasets)
    if (fitted_offset(set))
      out += fmt::format("  {:<{}}  {:>12.6g}  {:>12.6g}  {:<22}  {:<8}  {}\n", offset_label(set), width, 0.0, set.force_offset.value,
                         offset_error_text(set.force_offset), "N", "none");
  out += "\n";
  for (const DataSetFit& set : r.datasets) {
    if (!set.harmonic) {
      out += fmt::format("  {}: force residual RMS {:.3g} %, worst {:.3g} % of max |F|\n", set.path, 100.0 * set.err, 100.0 * set.worst);
      continue;
    }
    std::size_t worst = 0;
    for (std::size_t k = 1; k < set.residuals.stiffness.size(); ++k)
      if (std::hypot(set.residuals.stiffness[k], set.residuals.damping[k]) > std::hypot(set.residuals.stiffness[worst], set.residuals.damping[worst]))
        worst = k;
    out += fmt::format("  {}: phi (5.1) = {:.6g}, err (6.1) = {:.4e}\n", set.path, set.phi, set.err);
    if (!set.prediction.points.empty()) {
      const HarmonicPoint& p = set.prediction.points[worst];
      out += fmt::format("    worst point {:g} mm, {:g} Hz: stiffness {:+.2f} %, phase {:+.3f} deg\n", p.amplitude, p.frequency,
                         100.0 * set.residuals.stiffness[worst], degrees(p.measures.phase - set.measured_phase[worst]));
    }
  }
  if (r.datasets.size() > 1 && r.phi > 0.0) out += fmt::format("  all harmonic data: phi = {:.6g}, err = {:.4e}\n", r.phi, r.err);
  const auto& s = r.statistics;
  for (std::size_t g = 0; g < s.together.size(); ++g) out += together_note(r, s.together[g], s.undetermined.at(g));
  for (std::size_t a = 0; a < s.correlation.size(); ++a)
    for (std::size_t b = a + 1; b < s.correlation[a].size(); ++b)
      if (std::abs(s.correlation[a][b]) > 0.95)
        out += fmt::format("  strongly correlated: {} and {} (r = {:.3f})\n", parameter_of(r, r.free[a]).path, parameter_of(r, r.free[b]).path,
                           s.correlation[a][b]);
  for (const DataSetFit& set : r.datasets)
    for (std::size_t a = 0; fitted_offset(set) && a < set.force_offset.correlation.size() && a < r.free.size(); ++a)
      if (std::abs(set.force_offset.correlation[a]) > 0.95)
        out += fmt::format("  strongly correlated: {} and {} (r = {:.3f})\n", parameter_of(r, r.free[a]).path, offset_label(set),
                           set.force_offset.correlation[a]);
  out += fmt::format("  {} evaluations in {:.2f} s; {}\n", r.evaluations, r.wall_seconds,
                     r.interrupted ? "interrupted: these are the best values found so far" : fmt::format("optimizer status {}", r.status));
  if (r.non_finite > 0) out += fmt::format("  note: {} evaluations gave a non-finite objective and were rejected\n", r.non_finite);
  if (!r.first_failure.empty()) out += fmt::format("  note: the first that could not be simulated: {}\n", r.first_failure);
  return out;
}

std::string fit_report_json(const FitDescription& d, const FitResult& r) {
  using nlohmann::json;
  json j;
  j["model"] = r.network.model().name;
  j["source"] = d.source;
  j["method"] = d.method;
  j["objective"] = d.objective;
  j["optimizer"] = d.optimizer;
  j["seed"] = d.seed;
  j["status"] = r.status;
  j["interrupted"] = r.interrupted;
  j["time_limited"] = r.time_limited;
  j["evaluations"] = r.evaluations;
  j["non_finite_evaluations"] = r.non_finite;
  j["first_failure"] = r.first_failure;
  j["wall_seconds"] = r.wall_seconds;
  j["phi"] = r.phi;
  j["err"] = r.err;
  j["notes"] = r.notes;
  json together = json::array();  // groups of parameter paths that act only together
  for (const auto& group : r.statistics.together) {
    json paths = json::array();
    for (int k : group) paths.push_back(parameter_of(r, r.free.at(static_cast<std::size_t>(k))).path);
    together.push_back(paths);
  }
  j["not_identifiable_together"] = together;
  json parameters = json::array();
  const auto& all = r.network.model().parameters;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const lang::Parameter& p = all[i];
    json e{{"path", p.path},
           {"unit", written_unit(p)},
           {"start", in_written_unit(p, r.start_values[i])},
           {"start_from", std::find(r.yeoh_started.begin(), r.yeoh_started.end(), static_cast<int>(i)) != r.yeoh_started.end() ? "yeoh" : "given"},
           {"value", in_written_unit(p, r.network.parameter(static_cast<int>(i)))}};
    const auto it = std::find(r.free.begin(), r.free.end(), static_cast<int>(i));
    e["free"] = it != r.free.end();
    if (p.free) e["lower"] = in_written_unit(p, p.lower), e["upper"] = in_written_unit(p, p.upper);
    if (it != r.free.end()) {
      if (const BoundSide side = bound_reached(p, r.network.parameter(static_cast<int>(i))); side != BoundSide::none)
        e["at_bound"] = side == BoundSide::lower ? "lower" : "upper";
      const auto k = static_cast<std::size_t>(it - r.free.begin());
      if (k < r.statistics.standard_error.size() && std::isfinite(r.statistics.standard_error[k]))
        e["standard_error"] = in_written_unit(p, r.statistics.standard_error[k]);
      if (k < r.statistics.identifiable.size()) e["identifiable"] = static_cast<bool>(r.statistics.identifiable[k]);
    }
    parameters.push_back(e);
  }
  j["parameters"] = parameters;
  json names = json::array();
  for (int i : r.free) names.push_back(parameter_of(r, i).path);
  j["correlation"] = {{"parameters", names}, {"matrix", r.statistics.correlation}};
  json data = json::array();
  for (const DataSetFit& set : r.datasets) {
    json s{{"file", set.path}, {"kind", data_kind(set)}, {"weight", set.weight}, {"points", data_points(set)}, {"err", set.err}};
    if (!set.source.step.empty()) s["step"] = set.source.step;
    if (set.source.material) {
      s["area_mm2"] = set.source.area.value_or(0.0);
      s["height_mm"] = set.source.height.value_or(0.0);
    }
    if (!set.harmonic && set.force_offset.given) {
      json offset{{"value", set.force_offset.value}, {"unit", "N"}, {"free", set.force_offset.free}};
      if (set.force_offset.free) {
        if (std::isfinite(set.force_offset.standard_error)) offset["standard_error"] = set.force_offset.standard_error;
        offset["identifiable"] = set.force_offset.identifiable;
        if (!set.force_offset.correlation.empty()) offset["correlation"] = set.force_offset.correlation;
      }
      s["force_offset"] = offset;
    }
    if (set.harmonic) {
      s["phi"] = set.phi;
      json residuals = json::array();
      for (std::size_t k = 0; k < set.prediction.points.size(); ++k) {
        const HarmonicPoint& p = set.prediction.points[k];
        residuals.push_back({{"amplitude_mm", p.amplitude},
                             {"frequency_hz", p.frequency},
                             {"stiffness_measured", set.measured_stiffness[k]},
                             {"stiffness_model", p.measures.stiffness},
                             {"phase_measured_deg", degrees(set.measured_phase[k])},
                             {"phase_model_deg", degrees(p.measures.phase)},
                             {"stiffness_residual", set.residuals.stiffness[k]},
                             {"damping_residual", set.residuals.damping[k]}});
      }
      s["residuals"] = residuals;
    } else {
      s["residuals"] = {{"rms", set.err}, {"max", set.worst}};
    }
    data.push_back(s);
  }
  j["data"] = data;
  return j.dump(2) + "\n";
}

}  // namespace rheo::runtime
