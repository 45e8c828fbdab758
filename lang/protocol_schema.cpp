#include "lang/protocol_schema.hpp"

#include "lang/limits.hpp"
#include "lang/setting_values.hpp"

#include <fmt/format.h>

namespace rheo::lang {
namespace {

struct ProtocolSpec {
  ProtocolKind kind;
  std::string_view name;
  std::vector<SettingSpec> settings;
};

// Drive and measurement quantities within the physical ranges of limits.hpp.
SettingSpec amplitude(Shape shape, bool positive = true) {
  return {.key = "amplitude", .shape = shape, .dimension = dim::length, .required = true, .positive = positive,
          .lowest = positive ? min_amplitude : -max_amplitude, .highest = max_amplitude};
}
SettingSpec frequency(Shape shape) {
  return {.key = "frequency", .shape = shape, .dimension = dim::frequency, .required = true, .positive = true,
          .lowest = min_frequency, .highest = max_frequency};
}
SettingSpec whole(std::string_view key, int minimum, int maximum, int multiple_of = 0) {
  return {.key = key, .shape = Shape::integer, .dimension = dim::none, .minimum = minimum, .multiple_of = multiple_of, .maximum = maximum};
}

const std::vector<ProtocolSpec>& schema() {
  static const SettingSpec elements{"elements", Shape::identifier, dim::none, false, false, 0, 0, {"all", "none"}};
  static const SettingSpec format{"format", Shape::identifier, dim::none, false, false, 0, 0, {"csv", "json"}};
  static const SettingSpec solver{"solver", Shape::identifier, dim::none, false, false, 0, 0, {"auto", "fixed", "sundials"}};
  static const SettingSpec steps_per_cycle = whole("steps_per_cycle", 16, max_steps_per_cycle, 4);
  static const std::vector<ProtocolSpec> protocols{
      {ProtocolKind::harmonic, "harmonic",
       {frequency(Shape::list),
        amplitude(Shape::list),
        {"definition", Shape::identifier, dim::none, false, false, 0, 0, {"thesis", "first_harmonic"}},
        {"steady_state", Shape::identifier, dim::none, false, false, 0, 0, {"auto", "closed_form", "time_stepping"}},
        steps_per_cycle,
        whole("cycles_max", 1, max_cycles),
        {"tolerance", Shape::number, dim::none, false, true},
        elements, format, solver}},
      {ProtocolKind::static_triangle, "static",
       {{"velocity", Shape::single, dim::velocity, true, true},
        amplitude(Shape::list),
        whole("cycles", 1, max_cycles),
        {"dt", Shape::single, dim::time, false, true},
        elements, format, solver}},
      {ProtocolKind::quasistatic, "quasistatic",
       {frequency(Shape::single),
        amplitude(Shape::list),
        whole("cycles", 1, max_cycles),
        steps_per_cycle,
        elements, format, solver}},
      {ProtocolKind::history, "history",
       {{"file", Shape::string, dim::none, true},
        whole("substeps", 1, max_substeps),
        elements, format, solver}},
      {ProtocolKind::step, "step",
       {amplitude(Shape::single, false),
        {"duration", Shape::single, dim::time, true, true},
        {"dt", Shape::single, dim::time, false, true},
        {"rise", Shape::single, dim::time, false, true},
        elements, format, solver}},
  };
  return protocols;
}

const ProtocolSpec& spec(ProtocolKind kind) {
  for (const auto& p : schema())
    if (p.kind == kind) return p;
  return schema().front();
}

}  // namespace

std::optional<ProtocolKind> protocol_kind(const std::string& name) {
  for (const auto& p : schema())
    if (p.name == name) return p.kind;
  return std::nullopt;
}

std::string protocol_name(ProtocolKind kind) { return std::string(spec(kind).name); }

std::vector<std::string> protocol_names() {
  std::vector<std::string> out;
  for (const auto& p : schema()) out.emplace_back(p.name);
  return out;
}

std::vector<std::string> protocol_setting_keys(ProtocolKind kind) {
  std::vector<std::string> out;
  for (const auto& s : spec(kind).settings) out.emplace_back(s.key);
  return out;
}

std::optional<Setting> check_setting(ProtocolKind kind, const ast::SettingNode& node, std::vector<Diagnostic>& errors) {
  return check_keyed_setting(spec(kind).settings, spec(kind).name, node, errors);
}

Protocol check_protocol(ProtocolKind kind, const std::vector<ast::SettingNode>& settings, const SourceLocation& where,
                        std::vector<Diagnostic>& errors) {
  Protocol out{kind, {}, {}, where};
  for (const auto& node : settings) {
    const ast::SettingNode* first = nullptr;
    for (const auto& earlier : settings) {
      if (&earlier == &node) break;
      if (earlier.key == node.key && !first) first = &earlier;
    }
    if (first) {
      errors.push_back({node.where, fmt::format("duplicate setting '{}' (first given at line {}); give it once", node.key, first->where.line)});
      continue;
    }
    if (auto s = check_setting(kind, node, errors)) out.settings.push_back(std::move(*s));
  }
  for (const auto& s : spec(kind).settings) {
    if (!s.required) continue;
    bool given = false;
    for (const auto& node : settings) given = given || node.key == s.key;
    if (!given) errors.push_back({where, fmt::format("{} requires the setting '{}'; add `{} = ...`", spec(kind).name, s.key, s.key)});
  }
  return out;
}

}  // namespace rheo::lang
