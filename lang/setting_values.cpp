#include "lang/setting_values.hpp"

#include "lang/expressions.hpp"
#include "lang/names.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace rheo::lang {
namespace {

// Settings are constants: references are not allowed (bare names are identifiers).
std::optional<ResolvedReference> no_references(const ast::Expr& e, std::vector<Diagnostic>& errors) {
  errors.push_back({e.where, fmt::format("'{}' is not a value here; settings take numbers with units, e.g. 2 mm", e.path)});
  return std::nullopt;
}

// The range of S in UNIT (the one the value was written in; internal units when empty).
std::string allowed_range(const SettingSpec& s, const std::string& unit) {
  const auto bound = [&](double v) { return show_value(v, s.dimension, unit); };
  if (std::isfinite(s.lowest) && std::isfinite(s.highest)) return fmt::format("between {} and {}", bound(s.lowest), bound(s.highest));
  if (std::isfinite(s.lowest)) return fmt::format("at least {}", bound(s.lowest));
  return fmt::format("at most {}", bound(s.highest));
}

// One number of the setting in internal units; a free number takes `fallback_unit` if given.
std::optional<double> constant(const ast::Expr& e, const SettingSpec& s, const std::string& fallback_unit, std::vector<Diagnostic>& errors) {
  auto typed = compile_expression(
      e, [&](const ast::Expr& r) { return no_references(r, errors); }, errors);
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
  const std::string unit = literal_unit(e).empty() ? fallback_unit : literal_unit(e);  // as written, for messages
  if (!std::isfinite(value)) {
    errors.push_back({e.where, fmt::format("{} must be a finite number, got {}; write a value that fits in a double (|x| < 1.8e308 in "
                                           "internal units)",
                                           s.key, show_value(value, s.dimension, unit))});
    return std::nullopt;
  }
  if (s.positive && !(value > 0)) {
    // At a vanishing amplitude every friction element sticks: the limit is a tiny amplitude's point.
    const char* advice = s.key == "amplitude" && value == 0 ? "; for the small-amplitude limit give a tiny one, e.g. 1 um" : "";
    errors.push_back({e.where, fmt::format("{} must be positive, got {}{}", s.key, show_value(value, s.dimension, unit), advice)});
    return std::nullopt;
  }
  if (!(value >= s.lowest && value <= s.highest)) {
    errors.push_back({e.where, fmt::format("{} must be {}, got {}", s.key, allowed_range(s, unit), show_value(value, s.dimension, unit))});
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
  step_spec.lowest = -std::numeric_limits<double>::infinity();
  step_spec.highest = std::numeric_limits<double>::infinity();
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

bool check_paths(const ast::SettingNode& n, std::vector<PathItem>* paths, std::vector<Diagnostic>& errors) {
  using Kind = ast::SettingValue::Kind;
  const auto& v = n.value;
  const std::string example = fmt::format("e.g. `{} = [m1.k, m1.tau]`", n.key);
  if ((v.kind != Kind::expression && v.kind != Kind::list) || !v.unit.empty()) {
    errors.push_back({v.where, fmt::format("{} takes a list of parameter paths, {}", n.key, example)});
    return false;
  }
  bool ok = true;
  for (const auto& item : v.items) {
    if (item->kind != ast::Expr::Kind::reference) {
      errors.push_back({item->where, fmt::format("{} lists parameters by path, not values; {}", n.key, example)});
      ok = false;
    } else if (paths) {
      paths->push_back({item->path, item->where});
    }
  }
  return ok;
}

}  // namespace

bool check_file_name(const std::string& name, const SourceLocation& where, std::vector<Diagnostic>& errors) {
  if (name.empty()) {
    errors.push_back({where, "the file name is empty; write one, e.g. \"road.csv\""});
    return false;
  }
  for (const char c : name)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) {
      errors.push_back({where, fmt::format("the file name holds the control character 0x{:02X}; remove it", static_cast<unsigned char>(c))});
      return false;
    }
  return true;
}

bool check_setting_value(const ast::SettingNode& n, const SettingSpec& s, Setting& out, std::vector<Diagnostic>& errors,
                         std::vector<PathItem>* paths) {
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
      if (*value != std::floor(*value) || *value < s.minimum || *value > s.maximum || (s.multiple_of && std::fmod(*value, s.multiple_of) != 0)) {
        errors.push_back({v.where, fmt::format("{} must be a whole number from {} to {}{}, got {:g}", n.key, s.minimum, s.maximum,
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
      return check_file_name(v.text, v.where, errors);
    case Shape::text:
      if (v.kind != Kind::string) {
        errors.push_back({v.where, fmt::format("{} takes a text in double quotes", n.key)});
        return false;
      }
      out.text = v.text;
      return true;
    case Shape::paths: return check_paths(n, paths, errors);
  }
  return false;
}

std::optional<Setting> check_keyed_setting(const std::vector<SettingSpec>& specs, std::string_view what, const ast::SettingNode& node,
                                           std::vector<Diagnostic>& errors, std::vector<PathItem>* paths) {
  std::vector<std::string> keys;
  for (const auto& s : specs) {
    keys.emplace_back(s.key);
    if (s.key != node.key) continue;
    Setting out{node.key, {}, s.dimension, {}, node.where};
    if (!check_setting_value(node, s, out, errors, paths)) return std::nullopt;
    return out;
  }
  errors.push_back({node.where, fmt::format("unknown setting '{}' for {};{} accepted: {}", node.key, what, did_you_mean(node.key, keys), join(keys))});
  return std::nullopt;
}

}  // namespace rheo::lang
