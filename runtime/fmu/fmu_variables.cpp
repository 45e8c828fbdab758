#include "runtime/fmu/fmu_variables.hpp"

#include "lang/element_schema.hpp"
#include "lang/limits.hpp"
#include "runtime/core/errors.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>

namespace rheo::runtime::fmu {
namespace {

void collect_kinds(const lang::Element& element, std::map<std::string, lang::ElementKind>& kinds) {
  if (!element.path.empty()) kinds[element.path] = element.kind;
  for (const auto& child : element.children) collect_kinds(child, kinds);
}

// The element law's specification of parameter NAME of element kind KIND (its slots, the
// alternative given instead of the last slot, the one-sided split), or nullptr.
const lang::ParameterSpec* parameter_spec(lang::ElementKind kind, std::string_view name) {
  for (const auto& spec : lang::element_specs()) {
    if (spec.element_kind != kind) continue;
    for (const auto* list : {&spec.slots, &spec.alternative, &spec.split})
      for (const auto& p : *list)
        if (p.name == name) return &p;
  }
  return nullptr;
}

Variable parameter_variable(const lang::Parameter& p, int index, const std::map<std::string, lang::ElementKind>& kinds) {
  Variable v;
  v.name = p.path;
  v.reference = kFirstParameter + static_cast<unsigned>(index);
  v.causality = p.expression.is_constant() ? Causality::parameter : Causality::calculated_parameter;
  v.unit = lang::internal_unit(p.dimension);
  v.start = p.value;
  v.parameter = index;
  const auto dot = p.path.rfind('.');
  const lang::ParameterSpec* spec = nullptr;
  std::string owner;
  if (dot != std::string::npos) {
    if (const auto kind = kinds.find(p.path.substr(0, dot)); kind != kinds.end()) {
      spec = parameter_spec(kind->second, std::string_view(p.path).substr(dot + 1));
      owner = fmt::format(" of {} '{}'", lang::kind_word(kind->second), kind->first);
    }
  }
  const std::string quantity = spec ? std::string(spec->quantity) : std::string("parameter");
  const std::string where = p.where.line > 0 ? fmt::format(", line {}:{}", p.where.line, p.where.column) : std::string();
  if (p.free) {
    v.min = p.lower;
    v.max = p.upper;
    v.description = fmt::format("{}{}{}; identified in [{}, {}] {}", quantity, owner, where, p.lower, p.upper, v.unit);
  } else {
    if (spec && spec->positive) v.min = std::numeric_limits<double>::min();
    if (spec && std::isfinite(spec->below)) v.max = std::nextafter(spec->below, 0.0);
    v.description = fmt::format("{}{}{}", quantity, owner, where);
  }
  if (v.causality == Causality::calculated_parameter) v.description += "; computed from other parameters";
  return v;
}

// FNV-1a, 64 bits, from OFFSET.
std::uint64_t fnv1a(std::string_view text, std::uint64_t offset) {
  std::uint64_t h = offset;
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

}  // namespace

std::vector<Variable> fmu_variables(const lang::CheckedModel& model) {
  std::vector<Variable> out;
  out.push_back(Variable{.name = "u",
                         .reference = kInputU,
                         .causality = Causality::input,
                         .unit = "mm",
                         .start = 0.0,
                         .min = -lang::max_amplitude,
                         .max = lang::max_amplitude,
                         .description = "terminal displacement (the other terminal is ground)"});
  out.push_back(Variable{.name = "F",
                         .reference = kOutputF,
                         .causality = Causality::output,
                         .unit = "N",
                         .start = 0.0,
                         .min = std::nullopt,
                         .max = std::nullopt,
                         .description = "terminal force at the communication point"});
  out.push_back(Variable{.name = "v",
                         .reference = kInputV,
                         .causality = Causality::input,
                         .unit = "mm/s",
                         .start = 0.0,
                         .min = std::nullopt,
                         .max = std::nullopt,
                         .description = "terminal velocity over the next step, for hosts that provide it (0: u is held over the step)",
                         .derivative_of = kInputU});
  std::map<std::string, lang::ElementKind> kinds;
  collect_kinds(model.root, kinds);
  for (std::size_t i = 0; i < model.parameters.size(); ++i) {
    const lang::Parameter& p = model.parameters[i];
    if (p.path == "u" || p.path == "F" || p.path == "v" || p.path == "time")
      throw ModelError(fmt::format("{}parameter '{}' of model '{}' has the name of the FMU's {}; rename it to export the model", error_at(p.where),
                                   p.path, model.name,
                                   p.path == "u"   ? "input u (the displacement)"
                                   : p.path == "v" ? "input v (the velocity)"
                                   : p.path == "F" ? "output F (the force)"
                                                   : "independent variable time"));
    out.push_back(parameter_variable(p, static_cast<int>(i), kinds));
  }
  out.push_back(Variable{.name = "time",
                         .reference = static_cast<unsigned>(out.size()),
                         .causality = Causality::independent,
                         .unit = "s",
                         .start = 0.0,
                         .min = std::nullopt,
                         .max = std::nullopt,
                         .description = "time at the last communication point"});
  return out;
}

std::string fmu_guid(std::string_view rheo_version, std::string_view model_name, std::string_view source) {
  std::string text = fmt::format("rheo {}\nmodel {}\n", rheo_version, model_name);
  text.append(source);
  const std::uint64_t a = fnv1a(text, 0xcbf29ce484222325ULL), b = fnv1a(text, 0x84222325cbf29ce4ULL);
  return fmt::format("{{{:08x}-{:04x}-{:04x}-{:04x}-{:012x}}}", a >> 32, (a >> 16) & 0xffff, a & 0xffff, b >> 48, b & 0xffffffffffffULL);
}

}  // namespace rheo::runtime::fmu
