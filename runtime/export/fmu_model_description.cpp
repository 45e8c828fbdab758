#include "runtime/export/fmu_model_description.hpp"

#include "lang/units.hpp"
#include "runtime/fmu/fmu_variables.hpp"

#include <fmt/format.h>

#include <cmath>
#include <set>

namespace rheo::runtime::exporter {
namespace {

using fmu::Causality;
using fmu::Variable;

// <Unit> of an internal unit: N = kg*m/s^2 and mm = 1e-3 m, so a value of dimension
// N^f mm^l s^t is 10^(-3 l) kg^f m^(f + l) s^(t - 2 f) in SI base units.
std::string unit_definition(const std::string& unit) {
  const auto parsed = lang::parse_unit(unit);
  const lang::Dimension d = parsed ? parsed->dimension : lang::Dimension{};
  std::string base;
  auto exponent = [&](const char* name, int power) {
    if (power != 0) base += fmt::format(" {}=\"{}\"", name, power);
  };
  exponent("kg", d.force);
  exponent("m", d.force + d.length);
  exponent("s", d.time - 2 * d.force);
  if (d.length != 0) base += fmt::format(" factor=\"{}\"", std::pow(10.0, -3.0 * d.length));
  return fmt::format("    <Unit name=\"{}\">\n      <BaseUnit{}/>\n    </Unit>\n", xml_attribute(unit), base);
}

const char* causality_word(Causality c) {
  switch (c) {
    case Causality::input: return "input";
    case Causality::output: return "output";
    case Causality::parameter: return "parameter";
    case Causality::calculated_parameter: return "calculatedParameter";
  }
  return "?";
}

std::string scalar_variable(const Variable& v) {
  std::string attributes;
  switch (v.causality) {
    case Causality::input: attributes = " variability=\"continuous\""; break;
    case Causality::output: attributes = " variability=\"continuous\" initial=\"calculated\""; break;
    case Causality::parameter: attributes = " variability=\"fixed\" initial=\"exact\""; break;
    case Causality::calculated_parameter: attributes = " variability=\"fixed\" initial=\"calculated\""; break;
  }
  std::string real;
  if (!v.unit.empty()) real += fmt::format(" unit=\"{}\"", xml_attribute(v.unit));
  if (v.min) real += fmt::format(" min=\"{}\"", *v.min);
  if (v.max) real += fmt::format(" max=\"{}\"", *v.max);
  if (v.causality == Causality::input || v.causality == Causality::parameter) real += fmt::format(" start=\"{}\"", v.start);
  return fmt::format(
      "    <ScalarVariable name=\"{}\" valueReference=\"{}\" description=\"{}\" causality=\"{}\"{}>\n      <Real{}/>\n    </ScalarVariable>\n",
      xml_attribute(v.name), v.reference, xml_attribute(v.description), causality_word(v.causality), attributes, real);
}

}  // namespace

std::string xml_attribute(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\n': out += "&#10;"; break;
      case '\r': out += "&#13;"; break;
      case '\t': out += "&#9;"; break;
      default:
        // Other control characters are not XML 1.0 characters at all.
        if (static_cast<unsigned char>(c) < 0x20) out += "&#xFFFD;";
        else out += c;
    }
  }
  return out;
}

std::string fmi2_model_description(const lang::CheckedModel& model, const FmuDescription& d) {
  const std::vector<Variable> variables = fmu::fmu_variables(model);
  std::set<std::string> units;
  for (const auto& v : variables)
    if (!v.unit.empty()) units.insert(v.unit);
  const std::string description = fmt::format("rheo model {} from {}, exported by rheo {}. Source text:\n{}", model.name, d.source_name,
                                              d.rheo_version, d.source);
  std::string xml = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"{}\" guid=\"{}\"\n"
      "  description=\"{}\"\n"
      "  generationTool=\"rheo {}\" variableNamingConvention=\"structured\" numberOfEventIndicators=\"0\">\n"
      "  <CoSimulation modelIdentifier=\"{}\" needsExecutionTool=\"false\" canHandleVariableCommunicationStepSize=\"true\"\n"
      "    canInterpolateInputs=\"true\" maxOutputDerivativeOrder=\"0\" canRunAsynchronuously=\"false\"\n"
      "    canBeInstantiatedOnlyOncePerProcess=\"false\" canNotUseMemoryManagementFunctions=\"true\" canGetAndSetFMUstate=\"true\"\n"
      "    canSerializeFMUstate=\"true\" providesDirectionalDerivative=\"false\"/>\n"
      "  <UnitDefinitions>\n",
      xml_attribute(model.name), d.guid, xml_attribute(description), xml_attribute(d.rheo_version), d.model_identifier);
  for (const auto& u : units) xml += unit_definition(u);
  xml +=
      "  </UnitDefinitions>\n"
      "  <LogCategories>\n"
      "    <Category name=\"logStatusError\" description=\"every call that returns fmi2Error: what went wrong and what to do\"/>\n"
      "  </LogCategories>\n"
      "  <DefaultExperiment startTime=\"0\"/>\n"
      "  <ModelVariables>\n";
  for (const auto& v : variables) xml += scalar_variable(v);
  // ModelStructure indices are 1-based positions in ModelVariables: value reference + 1.
  xml +=
      "  </ModelVariables>\n"
      "  <ModelStructure>\n"
      "    <Outputs>\n";
  // F at a communication point depends on the network's state only, not on the input set after it.
  xml += fmt::format("      <Unknown index=\"{}\" dependencies=\"\"/>\n", fmu::kOutputF + 1);
  xml +=
      "    </Outputs>\n"
      "    <InitialUnknowns>\n";
  for (const auto& v : variables)
    if (v.causality == Causality::output || v.causality == Causality::calculated_parameter)
      xml += fmt::format("      <Unknown index=\"{}\"/>\n", v.reference + 1);
  xml +=
      "    </InitialUnknowns>\n"
      "  </ModelStructure>\n"
      "</fmiModelDescription>\n";
  return xml;
}

}  // namespace rheo::runtime::exporter
