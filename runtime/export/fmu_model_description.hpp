// modelDescription.xml of an exported FMU, FMI 2.0 co-simulation (the standard's section 2.2
// and 4.3; valid against fmi2ModelDescription.xsd): the variables of runtime/fmu/fmu_variables.hpp
// with their units (each defined in SI base units), start values and bounds; the model's source
// text and rheo's version in the description.
#pragma once

#include "lang/model.hpp"

#include <string>
#include <string_view>

namespace rheo::runtime::exporter {

struct FmuDescription {
  std::string model_identifier;  // the binary's name, binaries/linux64/MODEL_IDENTIFIER.so
  std::string guid;              // fmu_guid()
  std::string rheo_version;
  std::string source_name;  // the .rheo file's name, for the description
  std::string_view source;  // its text
};

std::string fmi2_model_description(const lang::CheckedModel& model, const FmuDescription& d);

// TEXT with &, <, >, " and the control characters an attribute would lose (newline, tab,
// carriage return) written as XML references.
std::string xml_attribute(std::string_view text);

}  // namespace rheo::runtime::exporter
