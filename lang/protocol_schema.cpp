#include "lang/protocol_schema.hpp"

#include "lang/expressions.hpp"
#include "lang/names.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>

namespace rheo::lang {
namespace {

enum class Shape {
  list,        // several values: a value, [list] or FROM .. TO step STEP
  single,      // exactly one value with a dimension
  integer,     // one whole plain number
  number,      // one plain number
  identifier,  // one of `choices`
  string,      // "text"
};

struct SettingSpec {
  std::string_view key;
  Shape shape;
  Dimension dimension;
  bool required = false;
  bool positive = false;      // list/single/number: every value > 0
  int minimum = 0;            // integer: value >= minimum
  int multiple_of = 0;        // integer: value % multiple_of == 0 when non-zero
  std::vector<std::string> choices = {};  // identifier
};

struct ProtocolSpec {
  ProtocolKind kind;
  std::string_view name;
  std::vector<SettingSpec> settings;
};

const std::vector<ProtocolSpec>& schema() {
  static const SettingSpec elements{"elements", Shape::identifier, dim::none, false, false, 0, 0, {"all", "none"}};
  static const SettingSpec format{"format", Shape::identifier, dim::none, false, false, 0, 0, {"csv", "json"}};
  static const std::vector<ProtocolSpec> protocols{
      {ProtocolKind::harmonic, "harmonic",
       {{"frequency", Shape::list, dim::frequency, true, true},
        {"amplitude", Shape::list, dim::length, true, true},
        {"definition", Shape::identifier, dim::none, false, false, 0, 0, {"thesis", "first_harmonic"}},
        {"steps_per_cycle", Shape::integer, dim::none, false, false, 16, 4},
        {"cycles_max", Shape::integer, dim::none, false, false, 1},
        {"tolerance", Shape::number, dim::none, false, true},
        elements, format}},
      {ProtocolKind::static_triangle, "static",
       {{"velocity", Shape::single, dim::velocity, true, true},
        {"amplitude", Shape::list, dim::length, true, true},
        {"cycles", Shape::integer, dim::none, false, false, 1},
        {"dt", Shape::single, dim::time, false, true},
        elements, format}},
      {ProtocolKind::quasistatic, "quasistatic",
       {{"frequency", Shape::single, dim::frequency, true, true},
        {"amplitude", Shape::list, dim::length, true, true},
        {"cycles", Shape::integer, dim::none, false, false, 1},
        {"steps_per_cycle", Shape::integer, dim::none, false, false, 16, 4},
        elements, format}},
      {ProtocolKind::history, "history",
       {{"file", Shape::string, dim::none, true},
        {"substeps", Shape::integer, dim::none, false, false, 1},
        elements, format}},
      {ProtocolKind::step, "step",
       {{"amplitude", Shape::single, dim::length, true},
        {"duration", Shape::single, dim::time, true, true},
        {"dt", Shape::single, dim::time, false, true},
        {"rise", Shape::single, dim::time},
        elements, format}},
  };
  return protocols;
}

const ProtocolSpec& spec(ProtocolKind kind) {
  for (const auto& p : schema())
    if (p.kind == kind) return p;
  return schema().front();
}

std::vector<std::string> keys(const ProtocolSpec& p) {
  std::vector<std::string> out;
  for (const auto& s : p.settings) out.emplace_back(s.key);
  return out;
}

// Settings are constants: references are not allowed (bare names are identifiers).
std::optional<ResolvedReference> no_references(const ast::Expr& e, std::vector<Diagnostic>& errors) {
  errors.push_back({e.where, fmt::format("'{}' is not a value here; settings take numbers with units, e.g. 2 mm", e.path)});
  return std::nullopt;
}

// One number of the setting in internal units; a free number takes `fallback_unit` if given.
std::optional<double> constant(const ast::Expr& e, const SettingSpec& s, const std::string& fallback_unit,
                               std::vector<Diagnostic>& errors) {
  auto typed = compile_expression(e, [&](const ast::Expr& r) { return no_references(r, errors); }, errors);
  if (!typed.ok) return std::nullopt;
  double value = typed.expression.evaluate({});
  if (typed.free && !fallback_unit.empty()) {
    auto unit = parse_unit(fallback_unit);
    if (!unit) {
      errors.push_back({e.where, fmt::format("unknown unit '{}'", fallback_unit)});
      return std::nullopt;
    }
    typed.free = false;
    typed.dimension = unit->dimension;
    value *= unit->scale;
  }
  if (!typed.free && typed.dimension != s.dimension) {
    errors.push_back({e.where, fmt::format("{} expects {}, got {}", s.key, with_article(s.dimension), with_article(typed.dimension))});
    return std::nullopt;
  }
  if (s.positive && !(value > 0)) {
    errors.push_back({e.where, fmt::format("{} must be positive, got {}", s.key, show_value(value, s.dimension, literal_unit(e)))});
    return std::nullopt;
  }
  return value;
}

// FROM .. TO step STEP, inclusive of TO when the last step lands within 1e-9 relative of it.
std::optional<std::vector<double>> expand_range(const ast::SettingNode& n, const SettingSpec& s, std::vector<Diagnostic>& errors) {
  auto from = constant(*n.value.items[0], s, "", errors);
  auto to = constant(*n.value.items[1], s, "", errors);
  SettingSpec step_spec = s;  // the step's own check below says what is wrong with it
  step_spec.positive = false;
  auto step = constant(*n.value.items[2], step_spec, "", errors);
  if (!from || !to || !step) return std::nullopt;
  if (!(*step > 0)) {
    errors.push_back({n.value.items[2]->where, "the step of a range must be positive"});
    return std::nullopt;
  }
  if (*to < *from) {
    errors.push_back({n.value.where, "the range is empty: its end is below its start"});
    return std::nullopt;
  }
  std::vector<double> out;
  const double tolerance = 1e-9 * std::max(std::abs(*from), std::abs(*to));
  for (long i = 0;; ++i) {
    double v = *from + static_cast<double>(i) * *step;
    if (v > *to + tolerance) break;
    out.push_back(std::abs(v - *to) <= tolerance ? *to : v);
    if (out.size() > 1000000) {
      errors.push_back({n.value.where, "the range has more than a million values; use a larger step"});
      return std::nullopt;
    }
  }
  return out;
}

bool single_value(const ast::SettingNode& n, std::string_view what, std::vector<Diagnostic>& errors) {
  if (n.value.kind == ast::SettingValue::Kind::expression) return true;
  errors.push_back({n.value.where, fmt::format("{} takes {}, not {}", n.key, what,
                                               n.value.kind == ast::SettingValue::Kind::string ? "a string" : "several values")});
  return false;
}

bool check_values(const ast::SettingNode& n, const SettingSpec& s, Setting& out, std::vector<Diagnostic>& errors) {
  using Kind = ast::SettingValue::Kind;
  const auto& v = n.value;
  switch (s.shape) {
    case Shape::list: {
      if (v.kind == Kind::string) {
        errors.push_back({v.where, fmt::format("{} takes values such as 2 mm or [1, 2] mm, not a string", n.key)});
        return false;
      }
      if (v.kind == Kind::range) {
        auto values = expand_range(n, s, errors);
        if (values) out.values = *values;
        return values.has_value();
      }
      bool ok = true;
      for (const auto& item : v.items) {
        auto value = constant(*item, s, v.unit, errors);
        if (value) out.values.push_back(*value);
        ok = ok && value;
      }
      return ok;
    }
    case Shape::single:
    case Shape::number: {
      if (!single_value(n, s.shape == Shape::single ? "a single value" : "a plain number", errors)) return false;
      auto value = constant(*v.items[0], s, "", errors);
      if (value) out.values.push_back(*value);
      return value.has_value();
    }
    case Shape::integer: {
      if (!single_value(n, "a whole number", errors)) return false;
      auto value = constant(*v.items[0], s, "", errors);
      if (!value) return false;
      if (*value != std::floor(*value) || *value < s.minimum || (s.multiple_of && std::fmod(*value, s.multiple_of) != 0)) {
        errors.push_back({v.where, fmt::format("{} must be a whole number >= {}{}, got {:g}", n.key, s.minimum,
                                               s.multiple_of ? fmt::format(" and a multiple of {}", s.multiple_of) : "", *value)});
        return false;
      }
      out.values.push_back(*value);
      return true;
    }
    case Shape::identifier: {
      const bool word = v.kind == Kind::expression && v.items[0]->kind == ast::Expr::Kind::reference;
      std::string text = word ? v.items[0]->path : std::string();
      for (const auto& c : s.choices)
        if (c == text) {
          out.text = text;
          return true;
        }
      errors.push_back({v.where, fmt::format("{} must be one of: {}{}", n.key, join(s.choices),
                                             word ? fmt::format(" (got '{}'){}", text, did_you_mean(text, s.choices)) : "")});
      return false;
    }
    case Shape::string:
      if (v.kind != Kind::string) {
        errors.push_back({v.where, fmt::format("{} takes a file name in double quotes, e.g. \"road.csv\"", n.key)});
        return false;
      }
      out.text = v.text;
      return true;
  }
  return false;
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

std::optional<Setting> check_setting(ProtocolKind kind, const ast::SettingNode& node, std::vector<Diagnostic>& errors) {
  const auto& p = spec(kind);
  for (const auto& s : p.settings) {
    if (s.key != node.key) continue;
    Setting out{node.key, {}, s.dimension, {}, node.where};
    if (!check_values(node, s, out, errors)) return std::nullopt;
    return out;
  }
  errors.push_back({node.where, fmt::format("unknown setting '{}' for {};{} accepted: {}", node.key, p.name,
                                            did_you_mean(node.key, keys(p)), join(keys(p)))});
  return std::nullopt;
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
