// What an exported FMU carries in its resources/ folder, and how its binary finds it from the
// fmuResourceLocation URI a host passes to fmi2Instantiate.
//   resources/model.rheo       the .rheo source as it was exported (every model of the file)
//   resources/model_name.txt   the name of the model the FMU runs (one line)
#pragma once

#include "runtime/fmu/cosimulation.hpp"

#include <memory>
#include <string>
#include <string_view>

namespace rheo::runtime::fmu {

inline constexpr const char* kSourceResource = "model.rheo";
inline constexpr const char* kModelNameResource = "model_name.txt";

// The local folder a `file:` URI names: "file:///a/b/resources/", "file:/a/b/resources",
// "file://localhost/a%20b/resources/" (percent-decoded). UsageError for another scheme, a remote
// host or a malformed escape.
std::string resource_folder(std::string_view uri);

// The co-simulation the files in FOLDER describe. DataError for a file that cannot be read;
// UsageError when GUID (the host's, from modelDescription.xml) is not fmu_guid() of what the files
// hold with RHEO_VERSION_TEXT (the binary's version): the resources were changed or come from
// another FMU. CompileError, ModelError from the model itself.
std::unique_ptr<CoSimulation> load_cosimulation(const std::string& folder, std::string_view guid, std::string_view rheo_version);

}  // namespace rheo::runtime::fmu
