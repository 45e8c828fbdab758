#include "lang/protocol_schema.hpp"

#include "lang/fit_schema.hpp"
#include "lang/limits.hpp"
#include "lang/setting_values.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace rheo::lang {
namespace {

struct ProtocolSpec {
  ProtocolKind kind;
  std::string_view name;
  std::vector<SettingSpec> settings;
};

// Drive and measurement quantities within the physical ranges of limits.hpp.
SettingSpec amplitude(Shape shape, bool positive = true) {
  return {.key = "amplitude",
          .shape = shape,
          .dimension = dim::length,
          .required = true,
          .positive = positive,
          .lowest = positive ? min_amplitude : -max_amplitude,
          .highest = max_amplitude};
}
SettingSpec frequency(Shape shape) {
  return {.key = "frequency",
          .shape = shape,
          .dimension = dim::frequency,
          .required = true,
          .positive = true,
          .lowest = min_frequency,
          .highest = max_frequency};
}
SettingSpec whole(std::string_view key, int minimum, int maximum, int multiple_of = 0) {
  return {.key = key, .shape = Shape::integer, .dimension = dim::none, .minimum = minimum, .multiple_of = multiple_of, .maximum = maximum};
}

const std::vector<ProtocolSpec>& schema() {
  static const SettingSpec elements{"elements", Shape::identifier, dim::none, false, false, 0, 0, {"all", "none"}};
  static const SettingSpec format{"format", Shape::identifier, dim::none, false, false, 0, 0, output_format_words()};
  static const SettingSpec solver{"solver", Shape::identifier, dim::none, false, false, 0, 0, solver_choice_words()};
  static const SettingSpec steps_per_cycle = whole("steps_per_cycle", 16, max_steps_per_cycle, 4);
  static const std::vector<ProtocolSpec> protocols{
      {ProtocolKind::harmonic,
       "harmonic",
       {frequency(Shape::list),
        amplitude(Shape::list),
        {"definition", Shape::identifier, dim::none, false, false, 0, 0, harmonic_definition_words()},
        {"steady_state", Shape::identifier, dim::none, false, false, 0, 0, steady_state_words()},
        steps_per_cycle,
        whole("cycles_max", 1, max_cycles),
        {"tolerance", Shape::number, dim::none, false, true},
        {"preload", Shape::single, dim::length, false, false},
        elements,
        format,
        solver}},
      {ProtocolKind::static_triangle,
       "static",
       {{"velocity", Shape::single, dim::velocity, true, true},
        amplitude(Shape::list),
        whole("cycles", 1, max_cycles),
        {"dt", Shape::single, dim::time, false, true},
        elements,
        format,
        solver}},
      {ProtocolKind::quasistatic,
       "quasistatic",
       {frequency(Shape::single), amplitude(Shape::list), whole("cycles", 1, max_cycles), steps_per_cycle, elements, format, solver}},
      {ProtocolKind::history,
       "history",
       {{"file", Shape::string, dim::none, true},
        {"columns", Shape::text, dim::none},
        whole("substeps", 1, max_substeps),
        {"start", Shape::identifier, dim::none, false, false, 0, 0, history_start_words()},
        elements,
        format,
        solver}},
      {ProtocolKind::step,
       "step",
       {amplitude(Shape::single, false),
        {"duration", Shape::single, dim::time, true, true},
        {"dt", Shape::single, dim::time, false, true},
        {"rise", Shape::single, dim::time, false, true},
        elements,
        format,
        solver}},
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

// The roles a history protocol's `columns` names.
static const std::vector<std::string>& history_column_roles() {
  static const std::vector<std::string> roles{"time", "displacement"};
  return roles;
}

std::optional<Setting> check_setting(ProtocolKind kind, const ast::SettingNode& node, std::vector<Diagnostic>& errors) {
  auto s = check_keyed_setting(spec(kind).settings, spec(kind).name, node, errors);
  if (s && s->key == "columns" && check_columns(*s, history_column_roles(), errors).empty()) return std::nullopt;
  return s;
}

Protocol check_protocol(ProtocolKind kind, const std::vector<ast::SettingNode>& settings, const SourceLocation& where,
                        std::vector<Diagnostic>& errors) {
  Protocol out{kind, {}, {}, {}, where};
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
    if (auto s = check_setting(kind, node, errors)) out.written.push_back(std::move(*s));
  }
  for (const auto& s : spec(kind).settings) {
    if (!s.required) continue;
    bool given = false;
    for (const auto& node : settings) given = given || node.key == s.key;
    if (!given) errors.push_back({where, fmt::format("{} requires the setting '{}'; add `{} = ...`", spec(kind).name, s.key, s.key)});
  }
  out.settings = decode_protocol_settings(kind, out.written);
  return out;
}

namespace {

// Reads the validated settings of one protocol line by key; absent keys leave a value as it is.
class Written {
 public:
  explicit Written(const std::vector<Setting>& settings) : settings_(settings) {}

  const Setting* find(std::string_view key) const {
    for (const auto& s : settings_)
      if (s.key == key) return &s;
    return nullptr;
  }
  void get(std::string_view key, double& value) const {
    if (const Setting* s = find(key); s && !s->values.empty()) value = s->values.front();
  }
  void get(std::string_view key, std::optional<double>& value) const {
    if (const Setting* s = find(key); s && !s->values.empty()) value = s->values.front();
  }
  void get(std::string_view key, int& value) const {
    if (const Setting* s = find(key); s && !s->values.empty()) value = static_cast<int>(s->values.front());
  }
  void get(std::string_view key, std::vector<double>& values) const {
    if (const Setting* s = find(key)) values = s->values;
  }
  template <class E>
  void get(std::string_view key, E& value, std::optional<E> (*named)(std::string_view)) const {
    if (const Setting* s = find(key))
      if (auto v = named(s->text)) value = *v;
  }

  void get_common(CommonSettings& c) const {
    if (const Setting* s = find("elements")) c.elements = s->text == "all";
    get("format", c.format, output_format_named);
    get("solver", c.solver, solver_choice_named);
  }

 private:
  const std::vector<Setting>& settings_;
};

}  // namespace

ProtocolSettings decode_protocol_settings(ProtocolKind kind, const std::vector<Setting>& written) {
  const Written w(written);
  switch (kind) {
    case ProtocolKind::harmonic: {
      HarmonicSettings h;
      w.get_common(h);
      w.get("frequency", h.frequencies);
      w.get("amplitude", h.amplitudes);
      w.get("definition", h.definition, harmonic_definition_named);
      w.get("steady_state", h.steady_state, steady_state_named);
      w.get("steps_per_cycle", h.steps_per_cycle);
      w.get("cycles_max", h.cycles_max);
      w.get("tolerance", h.tolerance);
      w.get("preload", h.preload);
      return h;
    }
    case ProtocolKind::static_triangle: {
      StaticSettings s;
      w.get_common(s);
      w.get("velocity", s.velocity);
      w.get("amplitude", s.amplitudes);
      w.get("cycles", s.cycles);
      w.get("dt", s.dt);
      return s;
    }
    case ProtocolKind::quasistatic: {
      QuasistaticSettings q;
      w.get_common(q);
      w.get("frequency", q.frequency);
      w.get("amplitude", q.amplitudes);
      w.get("cycles", q.cycles);
      w.get("steps_per_cycle", q.steps_per_cycle);
      return q;
    }
    case ProtocolKind::history: {
      HistorySettings h;
      w.get_common(h);
      if (const Setting* file = w.find("file")) h.file = file->text, h.file_where = file->where;
      if (const Setting* columns = w.find("columns")) {
        std::vector<Diagnostic> checked_before;  // check_setting reported any fault
        h.columns = check_columns(*columns, history_column_roles(), checked_before);
      }
      w.get("substeps", h.substeps);
      w.get("start", h.start, history_start_named);
      return h;
    }
    case ProtocolKind::step: {
      StepSettings s;
      w.get_common(s);
      w.get("amplitude", s.amplitude);
      w.get("duration", s.duration);
      s.dt = s.duration / 1000.0;
      w.get("dt", s.dt);
      s.rise = s.dt;
      w.get("rise", s.rise);
      return s;
    }
  }
  return HarmonicSettings{};
}

void override_setting(Protocol& protocol, Setting setting) {
  auto same_key = [&](const Setting& s) { return s.key == setting.key; };
  if (auto it = std::find_if(protocol.written.begin(), protocol.written.end(), same_key); it != protocol.written.end()) *it = std::move(setting);
  else protocol.written.push_back(std::move(setting));
  protocol.settings = decode_protocol_settings(protocol.kind, protocol.written);
}

}  // namespace rheo::lang
