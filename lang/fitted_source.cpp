#include "lang/fitted_source.hpp"

#include "lang/stdlib.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>
#include <stdexcept>

namespace rheo::lang {
namespace {

struct UnitChoice {
  std::string text;     // written after the number; "" for none
  double scale = 1.0;   // internal value per written value
  bool divide = false;  // a reciprocal unit such as 1/mm: written `V / 1 mm`
};

UnitChoice choose_unit(const Parameter& p) {
  if (auto u = parse_unit(p.unit); u && !p.unit.empty() && u->dimension == p.dimension) return {p.unit, u->scale};
  if (p.dimension.dimensionless()) return {};
  if (p.dimension == dim::frequency) return {"Hz", 1.0};
  std::string internal = internal_unit(p.dimension);
  if (parse_unit(internal)) return {internal, 1.0};
  return {internal_unit(dim::none / p.dimension), 1.0, true};  // 1/(N*mm^2) -> "V / 1 N*mm^2"
}

// Where P's value text is not its own, why (for the error), or "" when it is.
std::string not_writable(const Parameter& p, const std::string& file) {
  if (!p.expression.is_constant())
    return fmt::format("'{}' is computed from other parameters, so it cannot take a fitted value; fit the parameters it is computed from", p.path);
  if (p.value_begin >= 0 && p.where.file == file) return "";
  const std::string name = p.path.substr(p.path.rfind('.') + 1);
  return fmt::format(
      "the value of '{}' is not written for it in {} (it is the default of an instantiated model, at {}:{}, which every "
      "instance shares); override it where the model is instantiated, e.g. `{} = ... in [LO, HI]`, to write its fitted value",
      p.path, file, p.where.file, p.where.line, name);
}

// So that an error located in a stdlib module quotes its line.
void add_stdlib_source(SourceSet& sources, const std::string& file) {
  for (const auto& name : stdlib_names())
    if (file == stdlib_path(name)) sources.add(file, std::string(*stdlib_source(name)));
}

std::string header_lines(const std::vector<std::string>& header) {
  std::string out;
  for (const auto& entry : header) {
    std::size_t start = 0;
    do {
      std::size_t end = entry.find('\n', start);
      std::string line = entry.substr(start, end == std::string::npos ? std::string::npos : end - start);
      out += line.empty() ? "#\n" : "# " + line + "\n";
      start = end == std::string::npos ? std::string::npos : end + 1;
    } while (start != std::string::npos);
  }
  return out;
}

}  // namespace

std::string format_parameter_value(const Parameter& p, double value) {
  if (!std::isfinite(value)) throw std::logic_error(fmt::format("the value of '{}' is not finite ({})", p.path, value));
  const UnitChoice unit = choose_unit(p);
  const double written = value / unit.scale;
  std::string number;
  for (int digits = 10; digits <= 17; ++digits) {
    number = fmt::format("{:.{}g}", written, digits);
    const double back = std::strtod(number.c_str(), nullptr) * unit.scale;
    if (std::abs(back - value) <= 1e-13 * std::abs(value)) break;
  }
  if (unit.text.empty()) return number;
  return unit.divide ? fmt::format("{} / 1 {}", number, unit.text) : fmt::format("{} {}", number, unit.text);
}

std::string write_fitted_source(const std::string& source, const std::string& file, const CheckedModel& model, const std::vector<double>& values,
                                const std::vector<int>& changed, const std::vector<std::string>& header, const std::vector<FittedSetting>& settings) {
  if (values.size() != model.parameters.size())
    throw std::logic_error(
        fmt::format("write_fitted_source: {} values for the {} parameters of model '{}'", values.size(), model.parameters.size(), model.name));
  struct Edit {
    int begin, end;
    std::string text;
  };
  std::vector<Edit> edits;
  std::vector<Diagnostic> errors;
  SourceSet sources;
  sources.add(file, source);
  for (int i : std::set<int>(changed.begin(), changed.end())) {
    if (i < 0 || static_cast<std::size_t>(i) >= model.parameters.size())
      throw std::logic_error(fmt::format("write_fitted_source: parameter index {} out of range", i));
    const Parameter& p = model.parameters[static_cast<std::size_t>(i)];
    if (std::string why = not_writable(p, file); !why.empty()) {
      add_stdlib_source(sources, p.where.file);
      errors.push_back({p.where, why});
      continue;
    }
    if (static_cast<std::size_t>(p.value_end) > source.size() || p.value_end <= p.value_begin)
      throw std::logic_error(fmt::format("write_fitted_source: the value of '{}' lies outside the given source of {}", p.path, file));
    edits.push_back({p.value_begin, p.value_end, format_parameter_value(p, values[static_cast<std::size_t>(i)])});
  }
  if (!errors.empty()) throw CompileError(std::move(errors), sources);
  for (const FittedSetting& setting : settings) {
    if (setting.value_begin < 0 || setting.value_end < setting.value_begin || static_cast<std::size_t>(setting.value_end) > source.size())
      throw std::logic_error(fmt::format("write_fitted_source: a data-line setting's value lies outside the given source of {}", file));
    edits.push_back({setting.value_begin, setting.value_end, setting.text});
  }
  std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) { return a.begin > b.begin; });
  std::string out = source;
  int limit = static_cast<int>(source.size());
  for (const auto& e : edits) {
    if (e.end > limit) throw std::logic_error("write_fitted_source: two values share one expression");
    out.replace(static_cast<std::size_t>(e.begin), static_cast<std::size_t>(e.end - e.begin), e.text);
    limit = e.begin;
  }
  return header_lines(header) + out;
}

}  // namespace rheo::lang
