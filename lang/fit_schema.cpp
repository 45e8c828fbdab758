#include "lang/fit_schema.hpp"

#include "lang/limits.hpp"
#include "lang/names.hpp"
#include "lang/setting_values.hpp"
#include "lang/text_encoding.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>

namespace rheo::lang {
namespace {

const std::vector<SettingSpec>& fit_schema() {
  static const std::vector<SettingSpec> specs{
      {.key = "objective", .shape = Shape::identifier, .dimension = dim::none, .choices = fit_objective_words()},
      {.key = "stiffness_weight", .shape = Shape::number, .dimension = dim::none, .lowest = 0.0, .highest = 1.0},
      {.key = "method", .shape = Shape::identifier, .dimension = dim::none, .choices = fit_method_words()},
      {.key = "optimizer", .shape = Shape::identifier, .dimension = dim::none, .choices = optimizer_words()},
      {.key = "max_evaluations", .shape = Shape::integer, .dimension = dim::none, .minimum = 1},
      {.key = "starts", .shape = Shape::integer, .dimension = dim::none, .minimum = 1},
      {.key = "seed", .shape = Shape::integer, .dimension = dim::none, .minimum = 0},
      {.key = "tolerance", .shape = Shape::number, .dimension = dim::none, .positive = true},
      {.key = "time_limit", .shape = Shape::single, .dimension = dim::time, .positive = true},
      {.key = "definition", .shape = Shape::identifier, .dimension = dim::none, .choices = harmonic_definition_words()},
      {.key = "steps_per_cycle", .shape = Shape::integer, .dimension = dim::none, .minimum = 16, .multiple_of = 4, .maximum = max_steps_per_cycle},
      {.key = "solver", .shape = Shape::identifier, .dimension = dim::none, .choices = solver_choice_words()},
      {.key = "free", .shape = Shape::paths, .dimension = dim::none},
      {.key = "fixed", .shape = Shape::paths, .dimension = dim::none},
  };
  return specs;
}

const std::vector<SettingSpec>& data_schema() {
  static const std::vector<SettingSpec> specs{
      {.key = "weight", .shape = Shape::number, .dimension = dim::none, .lowest = 0.0},
      {.key = "columns", .shape = Shape::text, .dimension = dim::none},
      {.key = "step", .shape = Shape::text, .dimension = dim::none},
      {.key = "area", .shape = Shape::single, .dimension = dim::area, .positive = true},
      {.key = "height", .shape = Shape::single, .dimension = dim::length, .positive = true},
      {.key = "amplitude", .shape = Shape::single, .dimension = dim::length, .positive = true},
      {.key = "duplicates", .shape = Shape::identifier, .dimension = dim::none, .choices = duplicate_points_words()},
      {.key = "force_offset", .shape = Shape::single, .dimension = dim::force},
  };
  return specs;
}

// `force_offset = 120 N` (a force with its unit, any sign) or `force_offset = free`.
ForceOffsetSetting check_force_offset(const ast::SettingNode& node, std::vector<Diagnostic>& errors) {
  ForceOffsetSetting out{.given = true, .where = node.value.where, .value_begin = node.value.begin, .value_end = node.value.end};
  const auto& v = node.value;
  const std::string advice = "e.g. force_offset = 120 N, or force_offset = free to fit it";
  if (v.kind == ast::SettingValue::Kind::expression && v.items.at(0)->kind == ast::Expr::Kind::reference && v.items[0]->path == "free") {
    out.free = true;
    return out;
  }
  std::vector<Diagnostic> as_number, as_force;
  const SettingSpec plain{.key = "force_offset", .shape = Shape::single, .dimension = dim::none};
  if (check_keyed_setting({plain}, "a data line", node, as_number)) {  // internal units are not assumed for an offset
    errors.push_back({v.where, fmt::format("force_offset needs a force unit; {}", advice)});
    return out;
  }
  if (auto s = check_keyed_setting(data_schema(), "a data line", node, as_force)) {
    out.value = s->values.at(0);
    return out;
  }
  for (auto& e : as_force) {
    e.message += "; " + advice;
    errors.push_back(std::move(e));
  }
  return out;
}

bool is_path_list(const std::string& key) { return key == "free" || key == "fixed"; }

std::string duplicate(const ast::SettingNode& node, const SourceLocation& first) {
  return fmt::format("duplicate setting '{}' (first given at line {}); give it once", node.key, first.line);
}

std::string trimmed(std::string_view s) {
  const auto begin = s.find_first_not_of(" \t");
  if (begin == std::string_view::npos) return {};
  return std::string(s.substr(begin, s.find_last_not_of(" \t") - begin + 1));
}

// `k = 61.476 N/mm in [6.1476, 614.76]`: P's value in its unit with bounds a decade either side.
std::string bounded_example(const Parameter& p) {
  auto unit = parse_unit(p.unit);
  const double scale = unit && unit->dimension == p.dimension ? unit->scale : 1.0;
  const double v = p.value / scale;
  const double lo = v > 0 ? v / 10 : v < 0 ? v * 10 : -1.0;
  const double hi = v > 0 ? v * 10 : v < 0 ? -v * 10 : 1.0;
  return fmt::format("`{} = {} in [{:g}, {:g}]`", p.path.substr(p.path.rfind('.') + 1), show_value(p.value, p.dimension, p.unit), lo, hi);
}

// The free set of the fit of M: the bounded parameters (FREE_GIVEN: those listed in FREE),
// less those listed in FIXED. Errors at the offending names; the empty set at WHERE.
class FreeSet {
 public:
  FreeSet(const CheckedModel& m, std::vector<Diagnostic>& errors) : m_(m), errors_(errors) {}

  std::vector<int> resolve(bool free_given, const std::vector<PathItem>& free, const std::vector<PathItem>& fixed, bool ok,
                           const SourceLocation& where) {
    const std::size_t reported = errors_.size();
    std::set<int> chosen;
    if (!free_given)
      for (int i : default_free_parameters(m_)) chosen.insert(i);
    for (const auto& item : free) {
      int i = index(item);
      if (i >= 0 && fittable(i, item) && !chosen.insert(i).second)
        errors_.push_back({item.where, fmt::format("'{}' is listed twice in free; list it once", item.path)});
    }
    for (const auto& item : fixed)
      if (int i = index(item); i >= 0) chosen.erase(i);
    if (chosen.empty() && ok && errors_.size() == reported) {
      if (default_free_parameters(m_).empty()) {
        const Parameter* example = nullptr;
        for (const auto& p : m_.parameters)
          if (!example && p.expression.is_constant()) example = &p;
        errors_.push_back({where, fmt::format("the fit of model '{}' has nothing to fit: none of its parameters has bounds; "
                                              "give bounds to the parameters to fit{}",
                                              m_.name, example ? ", e.g. " + bounded_example(*example) : std::string())});
      } else {
        errors_.push_back({where, fmt::format("the fit of model '{}' has nothing to fit: `fixed` removes every free parameter; "
                                              "fix fewer or give more parameters bounds",
                                              m_.name)});
      }
    }
    return {chosen.begin(), chosen.end()};
  }

 private:
  int index(const PathItem& item) {
    std::vector<std::string> paths, bounded;
    for (std::size_t i = 0; i < m_.parameters.size(); ++i) {
      if (m_.parameters[i].path == item.path) return static_cast<int>(i);
      paths.push_back(m_.parameters[i].path);
      if (m_.parameters[i].free) bounded.push_back(m_.parameters[i].path);
    }
    errors_.push_back({item.where, fmt::format("model '{}' has no parameter '{}';{} {}", m_.name, item.path, did_you_mean(item.path, paths),
                                               !bounded.empty() ? "its parameters with bounds: " + join(bounded)
                                               : paths.empty()  ? std::string("it has no parameters")
                                                                : "parameters are named by path, e.g. " + paths.back())});
    return -1;
  }

  // A free parameter is a constant with bounds; reports why parameter I is not.
  bool fittable(int i, const PathItem& item) {
    const Parameter& p = m_.parameters[static_cast<std::size_t>(i)];
    if (!p.expression.is_constant()) {
      std::vector<std::string> inputs;
      for (const auto& op : p.expression.code)
        if (op.op == Expression::Op::parameter) {
          const std::string& path = m_.parameters[static_cast<std::size_t>(op.parameter)].path;
          if (std::find(inputs.begin(), inputs.end(), path) == inputs.end()) inputs.push_back(path);
        }
      errors_.push_back({item.where, inputs.size() == 1 ? fmt::format("'{}' is computed from '{}', so it cannot be fitted itself; fit '{}' instead: "
                                                                      "give it bounds and list it in free",
                                                                      p.path, inputs[0], inputs[0])
                                                        : fmt::format("'{}' is computed from {}, so it cannot be fitted itself; fit those instead: "
                                                                      "give them bounds and list them in free",
                                                                      p.path, join(inputs))});
      return false;
    }
    if (!p.free) {
      const bool shared = p.value_begin < 0;
      errors_.push_back(
          {item.where, fmt::format("parameter '{}' has no bounds; {} to fit it: {}", p.path,
                                   shared ? "override it with bounds where its model is instantiated" : "give it bounds", bounded_example(p))});
      return false;
    }
    return true;
  }

  const CheckedModel& m_;
  std::vector<Diagnostic>& errors_;
};

// The typed settings of a block from its validated settings lines (free/fixed excluded).
FitSettings decode_fit_settings(const std::vector<Setting>& written) {
  FitSettings out;
  for (const Setting& s : written) {
    const double number = s.values.empty() ? 0.0 : s.values.front();
    const auto whole = static_cast<int>(number);
    if (s.key == "objective") out.objective = fit_objective_named(s.text).value_or(out.objective);
    else if (s.key == "stiffness_weight") out.stiffness_weight = number;
    else if (s.key == "method") out.method = fit_method_named(s.text).value_or(out.method);
    else if (s.key == "optimizer") out.optimizer = optimizer_named(s.text).value_or(out.optimizer);
    else if (s.key == "max_evaluations") out.max_evaluations = whole;
    else if (s.key == "starts") out.starts = whole;
    else if (s.key == "seed") out.seed = whole;
    else if (s.key == "tolerance") out.tolerance = number;
    else if (s.key == "time_limit") out.time_limit = number;
    else if (s.key == "definition") out.definition = harmonic_definition_named(s.text).value_or(out.definition);
    else if (s.key == "steps_per_cycle") out.steps_per_cycle = whole;
    else if (s.key == "solver") out.solver = solver_choice_named(s.text).value_or(out.solver);
  }
  return out;
}

}  // namespace

FitData check_data_line(const ast::FitLine& line, std::vector<Diagnostic>& errors) {
  FitData out{line.file, 1.0, line.file_where, {}, {}, {}, {}, {}, false, DuplicatePoints::average, {}, line.end};
  check_file_name(line.file, line.file_where, errors);
  std::map<std::string, SourceLocation> seen;
  for (const auto& node : line.settings) {
    if (auto [it, fresh] = seen.emplace(node.key, node.where); !fresh) {
      errors.push_back({node.where, duplicate(node, it->second)});
      continue;
    }
    if (node.key == "amplitude") {  // a length, or a plain strain (0.1 %)
      std::vector<Diagnostic> as_length, as_strain;
      const SettingSpec strain{.key = "amplitude", .shape = Shape::single, .dimension = dim::none, .positive = true};
      if (auto length = check_keyed_setting(data_schema(), "a data line", node, as_length)) {
        out.amplitude = length->values.at(0);
      } else if (auto strain_value = check_keyed_setting({strain}, "a data line", node, as_strain)) {
        out.amplitude = strain_value->values.at(0);
        out.amplitude_is_strain = true;
      } else {
        for (auto& e : as_length) {
          e.message += "; or a strain, e.g. amplitude = 0.1 %";
          errors.push_back(std::move(e));
        }
      }
      continue;
    }
    if (node.key == "force_offset") {
      out.force_offset = check_force_offset(node, errors);
      continue;
    }
    const auto s = check_keyed_setting(data_schema(), "a data line", node, errors);
    if (!s) continue;
    if (s->key == "weight") out.weight = s->values.at(0);
    else if (s->key == "columns") out.columns = check_columns(*s, data_column_roles(), errors);
    else if (s->key == "step") out.step = s->text;
    else if (s->key == "area") out.area = s->values.at(0);
    else if (s->key == "height") out.height = s->values.at(0);
    else if (s->key == "duplicates") out.duplicates = duplicate_points_named(s->text).value_or(out.duplicates);
  }
  return out;
}

std::optional<Setting> check_fit_setting(const ast::SettingNode& node, std::vector<Diagnostic>& errors) {
  if (is_path_list(node.key)) {
    errors.push_back({node.where, fmt::format("'{}' names parameters of the fitted model; give it in the fit block", node.key)});
    return std::nullopt;
  }
  return check_keyed_setting(fit_schema(), "fit", node, errors);
}

// `columns = "frequency = f, storage = E_stor"`: ROLE = NAME pairs, each role once, of ROLES.
std::vector<ColumnName> check_columns(const Setting& s, const std::vector<std::string>& roles, std::vector<Diagnostic>& errors) {
  std::vector<ColumnName> out;
  const std::string example = roles.size() == 2 ? "e.g. columns = \"time = t, displacement = s\""
                                                : "e.g. columns = \"frequency = f, storage = E_stor, loss = E_loss\"";
  std::size_t start = 0;
  while (start <= s.text.size()) {
    auto comma = s.text.find(',', start);
    if (comma == std::string::npos) comma = s.text.size();
    const std::string pair = s.text.substr(start, comma - start);
    start = comma + 1;
    const auto equals = pair.find('=');
    const std::string role = trimmed(pair.substr(0, equals)), name = equals == std::string::npos ? "" : trimmed(pair.substr(equals + 1));
    if (equals == std::string::npos || role.empty() || name.empty()) {
      errors.push_back({s.where, fmt::format("columns takes 'role = column name' pairs separated by commas, {}; '{}' is not one", example,
                                             printable(trimmed(pair)))});
      return {};
    }
    if (std::find(roles.begin(), roles.end(), role) == roles.end()) {
      errors.push_back({s.where, fmt::format("columns: '{}' is not a role rheo reads; use {}", printable(role), join(roles))});
      return {};
    }
    for (const auto& earlier : out)
      if (earlier.role == role) {
        errors.push_back({s.where, fmt::format("columns names the '{}' column twice; name it once", role)});
        return {};
      }
    out.push_back({role, name});
  }
  return out;
}

const std::vector<std::string>& data_column_roles() {
  static const std::vector<std::string> roles{"time",  "displacement", "force", "amplitude", "frequency", "stiffness",
                                              "phase", "storage",      "loss",  "weight",    "preload"};
  return roles;
}

std::vector<std::string> fit_setting_keys() {
  std::vector<std::string> out;
  for (const auto& s : fit_schema()) out.emplace_back(s.key);
  return out;
}

FitDirective check_fit(const ast::Fit& fit, const std::string& model, const CheckedModel* checked, std::vector<Diagnostic>& errors) {
  FitDirective out{model, {}, {}, {}, {}, fit.where};
  std::vector<Setting> written;
  std::map<std::string, SourceLocation> seen;  // keys of the settings lines
  std::vector<PathItem> free, fixed;
  bool free_given = false;
  bool lists_ok = true;
  const ast::FitLine* output = nullptr;
  for (const auto& line : fit.lines) {
    if (line.kind == ast::FitLine::Kind::data) {
      out.data.push_back(check_data_line(line, errors));
    } else if (line.kind == ast::FitLine::Kind::output) {
      if (output) {
        errors.push_back({line.where, fmt::format("a fit block has one 'output' (first given at line {}); remove this one", output->where.line)});
      } else {
        out.output = line.file;
        output = &line;
        check_file_name(line.file, line.file_where, errors);
      }
    } else {
      for (const auto& node : line.settings) {
        if (auto [it, fresh] = seen.emplace(node.key, node.where); !fresh) {
          errors.push_back({node.where, duplicate(node, it->second)});
          continue;
        }
        if (node.key == "weight") {
          errors.push_back({node.where, "weight belongs to a data line: put it after the file name, `data \"FILE\", weight = 0.5`"});
          continue;
        }
        std::vector<PathItem>* paths = node.key == "free" ? &free : node.key == "fixed" ? &fixed : nullptr;
        auto setting = check_keyed_setting(fit_schema(), "fit", node, errors, paths);
        free_given = free_given || node.key == "free";
        if (!setting) lists_ok = lists_ok && !paths;
        else if (!paths) written.push_back(std::move(*setting));
      }
    }
  }
  if (checked) out.free = FreeSet(*checked, errors).resolve(free_given, free, fixed, lists_ok, fit.where);
  out.settings = decode_fit_settings(written);
  return out;
}

}  // namespace rheo::lang
