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
    case Causality::independent: return "independent";
  }
  return "?";
}

// V's variability and initial attributes, the same in FMI 2.0 and 3.0.
std::string variability_attributes(const Variable& v) {
  switch (v.causality) {
    case Causality::input: return " variability=\"continuous\"";
    case Causality::output: return " variability=\"continuous\" initial=\"calculated\"";
    case Causality::parameter: return " variability=\"fixed\" initial=\"exact\"";
    case Causality::calculated_parameter: return " variability=\"fixed\" initial=\"calculated\"";
    case Causality::independent: return " variability=\"continuous\"";
  }
  return "";
}

// V's unit, bounds and start (inputs and parameters): FMI 2.0's <Real>, FMI 3.0's <Float64>.
std::string value_attributes(const Variable& v) {
  std::string out;
  if (!v.unit.empty()) out += fmt::format(" unit=\"{}\"", xml_attribute(v.unit));
  if (v.min) out += fmt::format(" min=\"{}\"", *v.min);
  if (v.max) out += fmt::format(" max=\"{}\"", *v.max);
  if (v.causality == Causality::input || v.causality == Causality::parameter) out += fmt::format(" start=\"{}\"", v.start);
  return out;
}

// FMI 2.0's <Real derivative>: the 1-based position in ModelVariables of the variable V is the
// time derivative of (value reference + 1: FMI 2.0 omits time, the last).
std::string scalar_variable(const Variable& v) {
  const std::string derivative = v.derivative_of ? fmt::format(" derivative=\"{}\"", *v.derivative_of + 1) : "";
  return fmt::format(
      "    <ScalarVariable name=\"{}\" valueReference=\"{}\" description=\"{}\" causality=\"{}\"{}>\n      <Real{}{}/>\n    </ScalarVariable>\n",
      xml_attribute(v.name), v.reference, xml_attribute(v.description), causality_word(v.causality), variability_attributes(v), value_attributes(v),
      derivative);
}

// <Float64> of V (FMI 3.0 section 2.4.7): the attributes of an FMI 2.0 <ScalarVariable> and its
// <Real> in one element; `derivative` names a variable by its value reference.
std::string float64_variable(const Variable& v) {
  const std::string derivative = v.derivative_of ? fmt::format(" derivative=\"{}\"", *v.derivative_of) : "";
  return fmt::format("    <Float64 name=\"{}\" valueReference=\"{}\" description=\"{}\" causality=\"{}\"{}{}{}/>\n", xml_attribute(v.name),
                     v.reference, xml_attribute(v.description), causality_word(v.causality), variability_attributes(v), value_attributes(v),
                     derivative);
}

std::string unit_definitions(const std::vector<Variable>& variables) {
  std::set<std::string> units;
  for (const auto& v : variables)
    if (!v.unit.empty()) units.insert(v.unit);
  std::string xml = "  <UnitDefinitions>\n";
  for (const auto& u : units) xml += unit_definition(u);
  return xml + "  </UnitDefinitions>\n";
}

std::string description_text(const lang::CheckedModel& model, const FmuDescription& d) {
  return fmt::format("rheo model {} from {}, exported by rheo {}. Source text:\n{}", model.name, d.source_name, d.rheo_version, d.source);
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
  std::vector<Variable> variables = fmu::fmu_variables(model);
  // FMI 2.0 leaves the independent variable time implicit (section 2.2.7); it is the last.
  std::erase_if(variables, [](const Variable& v) { return v.causality == Causality::independent; });
  const std::string description = description_text(model, d);
  std::string xml = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"{}\" guid=\"{}\"\n"
      "  description=\"{}\"\n"
      "  generationTool=\"rheo {}\" variableNamingConvention=\"structured\" numberOfEventIndicators=\"0\">\n"
      "  <CoSimulation modelIdentifier=\"{}\" needsExecutionTool=\"false\" canHandleVariableCommunicationStepSize=\"true\"\n"
      "    canInterpolateInputs=\"true\" maxOutputDerivativeOrder=\"0\" canRunAsynchronuously=\"false\"\n"
      "    canBeInstantiatedOnlyOncePerProcess=\"false\" canNotUseMemoryManagementFunctions=\"true\" canGetAndSetFMUstate=\"true\"\n"
      "    canSerializeFMUstate=\"true\" providesDirectionalDerivative=\"false\"/>\n",
      xml_attribute(model.name), d.guid, xml_attribute(description), xml_attribute(d.rheo_version), d.model_identifier);
  xml += unit_definitions(variables);
  xml +=
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

std::string fmi3_model_description(const lang::CheckedModel& model, const FmuDescription& d) {
  const std::vector<Variable> variables = fmu::fmu_variables(model);
  std::string xml = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<fmiModelDescription fmiVersion=\"3.0\" modelName=\"{}\" instantiationToken=\"{}\"\n"
      "  description=\"{}\"\n"
      "  generationTool=\"rheo {}\" variableNamingConvention=\"structured\">\n"
      "  <CoSimulation modelIdentifier=\"{}\" needsExecutionTool=\"false\" canBeInstantiatedOnlyOncePerProcess=\"false\"\n"
      "    canGetAndSetFMUState=\"true\" canSerializeFMUState=\"true\" providesDirectionalDerivatives=\"false\"\n"
      "    providesAdjointDerivatives=\"false\" providesPerElementDependencies=\"false\" canHandleVariableCommunicationStepSize=\"true\"\n"
      "    maxOutputDerivativeOrder=\"0\" providesIntermediateUpdate=\"false\" mightReturnEarlyFromDoStep=\"false\"\n"
      "    canReturnEarlyAfterIntermediateUpdate=\"false\" hasEventMode=\"false\"/>\n",
      xml_attribute(model.name), d.guid, xml_attribute(description_text(model, d)), xml_attribute(d.rheo_version), d.model_identifier);
  xml += unit_definitions(variables);
  xml +=
      "  <LogCategories>\n"
      "    <Category name=\"logStatusError\" description=\"every call that returns fmi3Error: what went wrong and what to do\"/>\n"
      "  </LogCategories>\n"
      "  <DefaultExperiment startTime=\"0\"/>\n"
      "  <ModelVariables>\n";
  for (const auto& v : variables) xml += float64_variable(v);
  // ModelStructure names variables by value reference. F at a communication point depends on the
  // network's state only, not on the input set after it: no dependencies.
  xml += fmt::format(
      "  </ModelVariables>\n"
      "  <ModelStructure>\n"
      "    <Output valueReference=\"{}\" dependencies=\"\"/>\n",
      fmu::kOutputF);
  for (const auto& v : variables)
    if (v.causality == Causality::output || v.causality == Causality::calculated_parameter)
      xml += fmt::format("    <InitialUnknown valueReference=\"{}\"/>\n", v.reference);
  xml +=
      "  </ModelStructure>\n"
      "</fmiModelDescription>\n";
  return xml;
}

}  // namespace rheo::runtime::exporter
