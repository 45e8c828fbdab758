#include "lang/parameter_checks.hpp"

#include "lang/expressions.hpp"
#include "lang/names.hpp"

#include <fmt/format.h>

#include <cmath>
#include <optional>

namespace rheo::lang {
namespace {
std::string show(const Parameter& p, double value) { return show_value(value, p.dimension, p.unit); }
}  // namespace

std::string describe_element(std::string_view kind, const std::string& path) { return fmt::format("{} '{}'", kind, path); }

std::string describe_parameter(const Parameter& p, const ParameterMeta& meta) {
  if (meta.owner_kind.empty()) return fmt::format("parameter '{}'", p.path);
  auto dot = p.path.rfind('.');
  return fmt::format("{} of {}", p.path.substr(dot + 1), describe_element(meta.owner_kind, p.path.substr(0, dot)));
}

bool check_value(const Parameter& p, const ParameterMeta& meta, std::vector<Diagnostic>& errors) {
  const double v = p.value;
  if (!std::isfinite(v)) {
    errors.push_back({p.where, fmt::format("{} evaluates to {}; check for a division by zero", describe_parameter(p, meta), v)});
    return false;
  }
  if (meta.positive && !(v > 0)) {
    errors.push_back({p.where, fmt::format("{} {} must be positive, got {}", meta.quantity, describe_parameter(p, meta), show(p, v))});
    return false;
  }
  if (!(v < meta.below)) {
    errors.push_back({p.where, fmt::format("{} {} must be below {:g}, got {}", meta.quantity, describe_parameter(p, meta), meta.below, show(p, v))});
    return false;
  }
  return true;
}

bool check_bounds(Parameter& p, const ParameterMeta& meta, const ast::Bounds& b, std::vector<Diagnostic>& errors) {
  const std::string what = describe_parameter(p, meta);
  if (!p.expression.is_constant()) {
    errors.push_back(
        {b.where, fmt::format("{} is computed from other parameters, so it cannot have bounds; put the bounds on those parameters", what)});
    return false;
  }
  auto bound = [&](const ast::Expr& x) -> std::optional<double> {
    auto constant_only = [&](const ast::Expr& r) -> std::optional<ResolvedReference> {
      errors.push_back({r.where, fmt::format("bounds must be numbers, not references to parameters ('{}')", r.path)});
      return std::nullopt;
    };
    auto typed = compile_expression(x, constant_only, errors);
    if (!typed.ok) return std::nullopt;
    double value = typed.expression.evaluate({});
    if (typed.free) {
      auto unit = parse_unit(p.unit);
      return unit ? value * unit->scale : value;
    }
    if (typed.dimension != p.dimension) {
      errors.push_back({x.where, fmt::format("bound of {} expects {}, got {}", what, with_article(p.dimension), with_article(typed.dimension))});
      return std::nullopt;
    }
    return value;
  };
  auto lower = bound(*b.lower);
  auto upper = bound(*b.upper);
  if (!lower || !upper) return false;
  if (*lower >= *upper) {
    errors.push_back({b.lower->where, fmt::format("lower bound {} of {} must be below its upper bound {}", show(p, *lower), what, show(p, *upper))});
    return false;
  }
  if (meta.positive && !(*lower > 0)) {
    errors.push_back(
        {b.lower->where, fmt::format("{} {} must be positive, so its lower bound must be too, got {}", meta.quantity, what, show(p, *lower))});
    return false;
  }
  if (!(*upper < meta.below)) {
    errors.push_back({b.upper->where, fmt::format("{} {} must be below {:g}, so its upper bound must be too, got {}", meta.quantity, what,
                                                  meta.below, show(p, *upper))});
    return false;
  }
  if (p.value < *lower || p.value > *upper) {
    errors.push_back({p.where, fmt::format("{} = {} lies outside its bounds [{}, {}]", what, show(p, p.value), show(p, *lower), show(p, *upper))});
    return false;
  }
  p.free = true;
  p.lower = *lower;
  p.upper = *upper;
  return true;
}

}  // namespace rheo::lang
