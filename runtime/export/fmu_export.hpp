// `rheo export FILE --fmu OUT.fmu` (docs/cli.md#rheo-export): a Functional Mock-up Unit for
// co-simulation, FMI 2.0, that runs a model of FILE with rheo's fixed-step kernels:
//   modelDescription.xml              fmu_model_description.hpp
//   binaries/linux64/MODEL.so         fmu_binary.hpp: one shared library, the same for every model
//   resources/model.rheo, model_name.txt   what the library compiles at fmi2Instantiate
//                                     (runtime/fmu/fmu_resources.hpp)
//   documentation/licenses/fmi2-headers.txt   the notice of the FMI headers the library is built with
#pragma once

#include "lang/model.hpp"
#include "runtime/network/network.hpp"

#include <string>
#include <string_view>

namespace rheo::runtime::exporter {

// ModelError naming the element and its line:col where the FMU's fixed-step kernels cannot
// serve NETWORK, which rheo itself steps with SUNDIALS IDA: an inerter in the root block (driven
// directly, its force is the input's second derivative, impulsive at every communication point of a
// held or ramped input), or blocks nested deeper than kFixedStepMaxBlockDepth below the model's
// body (one Newton solve per level: the cost of a step grows geometrically with the depth).
void check_fmu_steppable(const Network& network);

struct FmuSource {
  std::string file_name;  // as given, for the description
  std::string_view text;  // the file's text, carried into resources/model.rheo
  std::string rheo_version;
};

// The bytes of the FMU (a ZIP archive) of MODEL, one of the models SOURCE compiles to. Calls
// check_fmu_steppable first.
std::string fmu_archive(const lang::CheckedModel& model, const FmuSource& source);

}  // namespace rheo::runtime::exporter
