#include "runtime/diagnosis/candidate_model.hpp"

#include "lang/source_edit.hpp"
#include "runtime/network/leaf_kernels.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rheo::runtime::diagnosis {
namespace {

std::string element_word(Effect effect) {
  switch (effect) {
    case Effect::amplitude_dependence: return "slip";
    case Effect::rate_dependence: return "relaxation";
    case Effect::nonlinear_elasticity: return "nonlinear";
    case Effect::coupled_amplitude_frequency: return "coupled";
    case Effect::inertia: return "resonance";
    case Effect::asymmetry: return "asymmetric";
    case Effect::backlash: return "backlash";
    case Effect::offset: return "offset";
    case Effect::none: break;
  }
  return "added";
}

std::string unique_name(const lang::CheckedModel& model, const std::string& word) {
  auto taken = [&](const std::string& name) {
    return std::any_of(model.root.children.begin(), model.root.children.end(), [&](const lang::Element& e) { return e.name == name; }) ||
           std::any_of(model.parameters.begin(), model.parameters.end(), [&](const lang::Parameter& p) { return p.path == name; });
  };
  std::string name = word;
  for (int k = 2; taken(name); ++k) name = fmt::format("{}{}", word, k);
  return name;
}

}  // namespace

int parameter_index(const lang::CheckedModel& model, const std::string& path) {
  for (std::size_t i = 0; i < model.parameters.size(); ++i)
    if (model.parameters[i].path == path) return static_cast<int>(i);
  return -1;
}

std::string candidate_name(const lang::CheckedModel& model, Effect effect) { return unique_name(model, element_word(effect)); }

std::string with_trial(const std::string& fitted_text, const lang::CheckedModel& fitted, const Trial& trial, const std::string& name,
                       const BoundScales& bounds, const std::string& comment) {
  const std::vector<std::string> lines = trial_statement(trial, name, bounds);
  if (trial.replaces.empty()) {
    std::vector<std::string> block{"# " + comment};
    block.insert(block.end(), lines.begin(), lines.end());
    return lang::append_to_model(fitted_text, fitted, block);
  }
  for (const auto& e : fitted.root.children)
    if (e.name == trial.replaces) {
      const lang::TextSpan span = lang::element_statement(fitted_text, e);
      const std::string indent = lang::line_indent(fitted_text, span.begin);
      std::string replacement = "# " + comment;
      for (const std::string& line : lines) replacement += "\n" + indent + line;
      return lang::replace_span(fitted_text, span, replacement);
    }
  throw std::logic_error(fmt::format("model '{}' has no root element '{}' to replace", fitted.name, trial.replaces));
}

std::string resolved_resonance(const Trial& trial, const lang::CheckedModel& model, const Network& network, const std::string& element,
                               const DataScales& scales) {
  if (trial.shape != Shape::tuned_column && trial.shape != Shape::capped_column) return {};
  const int k = parameter_index(model, element + ".chamber.k"), b = parameter_index(model, element + ".column.mass.b");
  if (k < 0 || b < 0) throw std::logic_error(fmt::format("diagnose: the fluid column '{}' lacks chamber.k or column.mass.b", element));
  const int walls = parameter_index(model, element + ".column.bulge.k");  // the column's node rests on k + k_b
  const double stiffness = network.parameter(k) + (walls >= 0 ? network.parameter(walls) : 0.0);
  const double resonance = std::sqrt(stiffness / network.parameter(b)) / (2.0 * std::numbers::pi);  // [Hz]
  constexpr double kMargin = 1.1;
  if (resonance >= kMargin * scales.frequency_low && resonance <= scales.frequency_high / kMargin) return {};
  return fmt::format(
      "its resonance, refitted to {:.3g} Hz, is not inside the measured {:.3g}-{:.3g} Hz with a measured frequency 10 % "
      "either side, so the data cannot tell it from a relaxation or a stiffness trend",
      resonance, scales.frequency_low, scales.frequency_high);
}

namespace {

// The refitted value of ELEMENT's parameter PATH (e.g. "cap.fy"); a candidate model without it is a bug.
double refitted_value(const lang::CheckedModel& model, const Network& refitted, const std::string& element, const std::string& path) {
  const int i = parameter_index(model, element + "." + path);
  if (i < 0) throw std::logic_error(fmt::format("diagnose: the candidate element '{}' lacks {}", element, path));
  return refitted.parameter(i);
}

}  // namespace

Trial resonance_free_limit(const Trial& column, const lang::CheckedModel& model, const Network& refitted, const std::string& element) {
  auto value = [&](const std::string& path) { return refitted_value(model, refitted, element, path); };
  Trial limit = column;
  limit.shape = Shape::capped_maxwell;
  limit.stiffness = value("chamber.k");
  limit.time = value("column.channel.c") / limit.stiffness;
  limit.slip = value("cap.fy") / limit.stiffness;
  limit.frequency = limit.damping_ratio = 0.0;
  return limit;
}

Trial column_from_limit(const Trial& column, const lang::CheckedModel& model, const Network& refitted, const std::string& element) {
  auto value = [&](const std::string& path) { return refitted_value(model, refitted, element, path); };
  Trial restart = column;
  restart.shape = Shape::capped_column;
  restart.stiffness = value("arm.k");
  restart.slip = value("cap.fy") / restart.stiffness;
  restart.time = 0.0;
  restart.damping_ratio = std::numbers::pi * column.frequency * value("arm.tau");
  return restart;
}

Trial friction_limit(const Trial& arm, const lang::CheckedModel& model, const Network& refitted, const std::string& element) {
  auto value = [&](const std::string& path) { return refitted_value(model, refitted, element, path); };
  Trial limit = arm;
  limit.effect = Effect::amplitude_dependence;
  limit.shape = Shape::friction;
  limit.stiffness = value("arm.k");
  limit.slip = value("cap.fy") / limit.stiffness;
  limit.time = limit.frequency = limit.damping_ratio = 0.0;
  return limit;
}

bool outlasts_sticking(const lang::CheckedModel& model, const Network& refitted, const std::string& element, const std::vector<FitDataSet>& data) {
  auto value = [&](const std::string& path) { return refitted_value(model, refitted, element, path); };
  return value("arm.tau") > longest_stick(data, value("cap.fy") / value("arm.k"));
}

std::optional<std::vector<double>> roles_exchanged(const lang::CheckedModel& model, const Network& refitted, const std::string& element,
                                                   const lang::Element& friction) {
  if (friction.kind != lang::ElementKind::friction || friction.parameters.size() != 2) return std::nullopt;
  const int arm_k = parameter_index(model, element + ".arm.k"), cap_fy = parameter_index(model, element + ".cap.fy");
  const int friction_k = friction.parameters[0], friction_uy = parameter_index(model, friction.name + ".uy");
  const int friction_yield = friction_uy >= 0 ? friction_uy : friction.parameters[1];  // uy where given, else fy
  auto free = [&](int i) { return i >= 0 && model.parameters[static_cast<std::size_t>(i)].free; };
  if (!free(arm_k) || !free(cap_fy) || !free(friction_k) || !free(friction_yield)) return std::nullopt;
  std::vector<double> values = refitted.parameters();
  auto at = [&](int i) -> double& { return values[static_cast<std::size_t>(i)]; };
  const double k_arm = at(arm_k), fy_arm = at(cap_fy);
  const double k_friction = at(friction_k), fy_friction = refitted.parameter(friction.parameters[1]);
  auto set = [&](int i, double v) {  // within the parameter's bounds
    const lang::Parameter& p = model.parameters[static_cast<std::size_t>(i)];
    at(i) = std::clamp(v, p.lower, p.upper);
  };
  set(arm_k, k_friction), set(cap_fy, fy_friction);
  set(friction_k, k_arm);
  set(friction_yield, friction_uy >= 0 ? fy_arm / k_arm : fy_arm);
  return values;
}

double longest_stick(const std::vector<FitDataSet>& data, double uy) {
  double longest = 0.0;
  for (const auto& set : data) {
    if (set.is_harmonic()) {
      const HarmonicData& h = set.harmonic();
      for (std::size_t i = 0; i < h.amplitude.size(); ++i)
        if (h.amplitude[i] > uy)
          longest = std::max(longest, std::acos(1.0 - 2.0 * uy / h.amplitude[i]) / (2.0 * std::numbers::pi * h.frequency[i]));
      continue;
    }
    const auto& u = set.history().drive.displacement;
    const auto& t = set.history().drive.time;
    for (std::size_t k = 1; k + 1 < u.size(); ++k) {
      if (!((u[k] - u[k - 1]) * (u[k + 1] - u[k]) < 0.0)) continue;  // not a turning point
      for (std::size_t j = k + 1; j < u.size(); ++j) {
        if (const double moved = std::abs(u[j] - u[k]); moved >= 2.0 * uy) {  // between samples j - 1 and j, linearly
          const double before = std::abs(u[j - 1] - u[k]);
          longest = std::max(longest, t[j - 1] - t[k] + (t[j] - t[j - 1]) * (2.0 * uy - before) / (moved - before));
          break;
        }
        if (j + 1 < u.size() && (u[j] - u[j - 1]) * (u[j + 1] - u[j]) < 0.0) break;  // turned again before slipping
      }
    }
  }
  return longest;
}

Trial bulged_column(const Trial& column, const lang::CheckedModel& model, const Network& refitted, const std::string& element) {
  auto value = [&](const std::string& path) { return refitted_value(model, refitted, element, path); };
  Trial bulged = column;
  bulged.shape = Shape::capped_column;
  bulged.stiffness = value("chamber.k");
  const double b = value("column.mass.b");  // trial.cpp: b = k / (2 pi f)^2, c = 2 zeta sqrt(k b)
  bulged.frequency = std::sqrt(bulged.stiffness / b) / (2.0 * std::numbers::pi);
  bulged.damping_ratio = value("column.channel.c") / (2.0 * std::sqrt(bulged.stiffness * b));
  bulged.slip = value("cap.fy") / bulged.stiffness;
  bulged.time = 0.0;
  bulged.bulge = kBulgeStart * bulged.stiffness;
  return bulged;
}

Network with_gaps_in_play(const Network& network) {
  const Topology& t = network.topology();
  std::vector<double> values = network.parameters();
  bool moved = false;
  for (const TreeNode& n : t.nodes) {
    if (n.kind != NodeKind::gap) continue;
    const auto c = static_cast<std::size_t>(n.param[1]);
    const double center = gap_center(network.parameter(n.param[0]), network.parameter(n.param[1]));
    const lang::Parameter& p = network.model().parameters[c];
    if (center != values[c] && (!p.free || (center >= p.lower && center <= p.upper))) values[c] = center, moved = true;
  }
  return moved ? network.with_parameters(values) : network;
}

}  // namespace rheo::runtime::diagnosis
