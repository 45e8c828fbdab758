// The FMI 2.0 co-simulation entry points of an exported FMU's binary, written from the FMI 2.0.4
// specification (sections 2.1 and 4): the common functions and those of co-simulation, with the
// standard's names and C calling convention (third_party/fmi2/fmi2Functions.h declares them and
// exports them from the shared library; beside them only the fmi3* functions of
// fmi3_entry_points.cpp are visible).
//
// Each call runs CoSimulation (cosimulation.hpp) under fmu_instance.hpp's guard: a UserError
// becomes fmi2Error with its message logged under category logStatusError, memory exhaustion
// fmi2Fatal. Messages are escaped for the logger's printf-style format ('%' as "%%") and the
// standard's variable references ('#' as "##").
#include "fmi2Functions.h"

#include "runtime/core/errors.hpp"
#include "runtime/fmu/cosimulation.hpp"
#include "runtime/fmu/fmu_instance.hpp"
#include "runtime/fmu/fmu_resources.hpp"

#include <fmt/format.h>

#include <cstring>
#include <memory>
#include <string>
#include <utility>

namespace __gnu_cxx {
void __freeres();  // libstdc++'s own (what valgrind calls at exit); no header declares it
}

namespace {

// libstdc++, linked in statically, allocates a 72 KB arena for exceptions thrown when memory runs
// out (its emergency pool) when the library is loaded. Freed when the host unloads the FMU, so
// that loading and unloading it does not lose the arena each time.
[[gnu::destructor]] void free_exception_pool() { __gnu_cxx::__freeres(); }

using rheo::runtime::fmu::FmiVersion;
using rheo::runtime::fmu::kErrorCategory;
using rheo::runtime::fmu::no_variables_of;
using rheo::runtime::fmu::Outcome;
using rheo::runtime::fmu::require_array;

std::string escaped(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    if (c == '%' || c == '#') out += c;
    out += c;
  }
  return out;
}

void log_error(fmi2CallbackLogger logger, fmi2ComponentEnvironment environment, const char* instance, const std::string& message) {
  if (logger) logger(environment, instance, fmi2Error, kErrorCategory, escaped(message).c_str());
}

struct Instance final : rheo::runtime::fmu::FmuInstance {
  using FmuInstance::FmuInstance;
  fmi2CallbackFunctions callbacks{};
  void log_error(const std::string& message) const override {
    ::log_error(callbacks.logger, callbacks.componentEnvironment, name().c_str(), message);
  }
};

// Runs BODY on the instance C; fmi2OK, or the status of what it threw, logged.
template <class Body>
fmi2Status guarded(fmi2Component c, const char* function, Body&& body) {
  if (!c) return fmi2Error;
  switch (rheo::runtime::fmu::guarded(*static_cast<Instance*>(c), function, std::forward<Body>(body))) {
    case Outcome::ok: return fmi2OK;
    case Outcome::fatal: return fmi2Fatal;
    case Outcome::error: break;
  }
  return fmi2Error;
}

// The co-simulation of the instance C (non-null), for the fast paths of the calls a host makes
// every step (cosimulation.hpp), tried before the guard: taken, they cannot fail.
rheo::runtime::fmu::CoSimulation& cosimulation(fmi2Component c) { return *static_cast<Instance*>(c)->cosimulation; }

}  // namespace

extern "C" {

const char* fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char* fmi2GetVersion(void) { return fmi2Version; }

// Errors are logged whatever loggingOn says, and nothing else is: the call checks the categories.
fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean /*loggingOn*/, size_t nCategories, const fmi2String categories[]) {
  return guarded(c, "fmi2SetDebugLogging", [&](Instance&) {
    require_array(categories, nCategories, "categories");
    for (size_t k = 0; k < nCategories; ++k)
      if (!categories[k] || std::strcmp(categories[k], kErrorCategory) != 0)
        throw rheo::UsageError(fmt::format("unknown log category '{}'; the FMU logs {}", categories[k] ? categories[k] : "(null)", kErrorCategory));
  });
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID, fmi2String fmuResourceLocation,
                              const fmi2CallbackFunctions* functions, fmi2Boolean /*visible*/, fmi2Boolean /*loggingOn*/) {
  const fmi2CallbackLogger logger = functions ? functions->logger : nullptr;
  fmi2ComponentEnvironment environment = functions ? functions->componentEnvironment : nullptr;
  const char* name = instanceName ? instanceName : "";
  try {
    if (fmuType != fmi2CoSimulation) throw rheo::UsageError("this FMU is for co-simulation only (fmuType fmi2CoSimulation)");
    if (!fmuGUID) throw rheo::UsageError("fmuGUID is NULL; pass the guid of modelDescription.xml");
    if (!fmuResourceLocation) throw rheo::UsageError("fmuResourceLocation is NULL; the FMU reads its model from its resources folder");
    auto instance = std::make_unique<Instance>(name);
    if (functions) instance->callbacks = *functions;
    instance->cosimulation = rheo::runtime::fmu::load_cosimulation(rheo::runtime::fmu::resource_folder(fmuResourceLocation), fmuGUID, RHEO_VERSION,
                                                                   FmiVersion::fmi2);
    return instance.release();
  } catch (const rheo::UserError& e) {
    log_error(logger, environment, name, fmt::format("fmi2Instantiate: {}", e.what()));
  } catch (const std::exception& e) {
    log_error(logger, environment, name, fmt::format("fmi2Instantiate: internal error: {}; please report it to rheo with the FMU", e.what()));
  }
  return nullptr;
}

void fmi2FreeInstance(fmi2Component c) { delete static_cast<Instance*>(c); }

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean /*toleranceDefined*/, fmi2Real /*tolerance*/, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
  // The kernels are exact for the input path: a tolerance changes nothing.
  return guarded(c, "fmi2SetupExperiment", [&](Instance& i) {
    i.cosimulation->setup_experiment(startTime, stopTimeDefined ? std::optional<double>(stopTime) : std::nullopt);
  });
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
  return guarded(c, "fmi2EnterInitializationMode", [](Instance& i) { i.cosimulation->enter_initialization(); });
}
fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
  return guarded(c, "fmi2ExitInitializationMode", [](Instance& i) { i.cosimulation->exit_initialization(); });
}
fmi2Status fmi2Terminate(fmi2Component c) {
  return guarded(c, "fmi2Terminate", [](Instance& i) { i.cosimulation->terminate(); });
}
fmi2Status fmi2Reset(fmi2Component c) {
  return guarded(c, "fmi2Reset", [](Instance& i) { i.cosimulation->reset(); });
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]) {
  if (c && nvr == 1 && vr && value && cosimulation(c).get_output_fast(vr[0], value[0])) return fmi2OK;
  return guarded(c, "fmi2GetReal", [&](Instance& i) {
    require_array(vr, nvr, "vr");
    require_array(value, nvr, "value");
    for (size_t k = 0; k < nvr; ++k) value[k] = i.cosimulation->get_real(vr[k]);
  });
}
fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference[], size_t nvr, fmi2Integer[]) {
  return guarded(c, "fmi2GetInteger", [&](Instance&) { no_variables_of("Integer", nvr); });
}
fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference[], size_t nvr, fmi2Boolean[]) {
  return guarded(c, "fmi2GetBoolean", [&](Instance&) { no_variables_of("Boolean", nvr); });
}
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference[], size_t nvr, fmi2String[]) {
  return guarded(c, "fmi2GetString", [&](Instance&) { no_variables_of("String", nvr); });
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]) {
  if (c && nvr == 1 && vr && value && cosimulation(c).set_input_fast(vr[0], value[0])) return fmi2OK;
  return guarded(c, "fmi2SetReal", [&](Instance& i) {
    require_array(vr, nvr, "vr");
    require_array(value, nvr, "value");
    for (size_t k = 0; k < nvr; ++k) i.cosimulation->set_real(vr[k], value[k]);
  });
}
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference[], size_t nvr, const fmi2Integer[]) {
  return guarded(c, "fmi2SetInteger", [&](Instance&) { no_variables_of("Integer", nvr); });
}
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference[], size_t nvr, const fmi2Boolean[]) {
  return guarded(c, "fmi2SetBoolean", [&](Instance&) { no_variables_of("Boolean", nvr); });
}
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference[], size_t nvr, const fmi2String[]) {
  return guarded(c, "fmi2SetString", [&](Instance&) { no_variables_of("String", nvr); });
}

// FMU states: FmuInstance's, handed to the host until it frees them (or frees the instance).
fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate* FMUstate) {
  return guarded(c, "fmi2GetFMUstate", [&](Instance& i) {
    require_array(FMUstate, 1, "FMUstate");
    if (*FMUstate) i.state(*FMUstate) = i.cosimulation->snapshot();
    else *FMUstate = i.new_state(i.cosimulation->snapshot());
  });
}
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate) {
  return guarded(c, "fmi2SetFMUstate", [&](Instance& i) { i.cosimulation->restore(i.state(FMUstate)); });
}
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate* FMUstate) {
  return guarded(c, "fmi2FreeFMUstate", [&](Instance& i) { i.free_state(FMUstate); });
}
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate, size_t* size) {
  return guarded(c, "fmi2SerializedFMUstateSize", [&](Instance& i) {
    require_array(size, 1, "size");
    *size = i.cosimulation->serialize(i.state(FMUstate)).size();
  });
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate, fmi2Byte serializedState[], size_t size) {
  return guarded(c, "fmi2SerializeFMUstate", [&](Instance& i) {
    const std::string bytes = i.cosimulation->serialize(i.state(FMUstate));
    if (size < bytes.size())
      throw rheo::UsageError(fmt::format("the buffer holds {} bytes; the state needs {} (fmi2SerializedFMUstateSize)", size, bytes.size()));
    require_array(serializedState, bytes.size(), "serializedState");
    std::memcpy(serializedState, bytes.data(), bytes.size());
  });
}
// Always a new state: the standard has the FMU construct one, whatever *FMUstate holds on entry.
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[], size_t size, fmi2FMUstate* FMUstate) {
  return guarded(c, "fmi2DeSerializeFMUstate", [&](Instance& i) {
    require_array(serializedState, size, "serializedState");
    require_array(FMUstate, 1, "FMUstate");
    *FMUstate = i.new_state(i.cosimulation->deserialize(std::string_view(serializedState, size)));
  });
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference[], size_t, const fmi2ValueReference[], size_t, const fmi2Real[],
                                        fmi2Real[]) {
  return guarded(c, "fmi2GetDirectionalDerivative",
                 [](Instance&) { throw rheo::UsageError("the FMU provides no directional derivatives (providesDirectionalDerivative false)"); });
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer order[], const fmi2Real value[]) {
  if (c && nvr == 1 && vr && order && value && cosimulation(c).set_rate_fast(vr[0], order[0], value[0])) return fmi2OK;
  return guarded(c, "fmi2SetRealInputDerivatives", [&](Instance& i) {
    require_array(vr, nvr, "vr");
    require_array(order, nvr, "order");
    require_array(value, nvr, "value");
    for (size_t k = 0; k < nvr; ++k) i.cosimulation->set_input_derivative(vr[k], order[k], value[k]);
  });
}
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t nvr, const fmi2Integer[], fmi2Real[]) {
  return guarded(c, "fmi2GetRealOutputDerivatives", [&](Instance&) {
    if (nvr > 0) throw rheo::UsageError("the FMU provides no output derivatives (maxOutputDerivativeOrder 0)");
  });
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean /*noSetFMUStatePriorToCurrentPoint*/) {
  return guarded(c, "fmi2DoStep", [&](Instance& i) { i.cosimulation->do_step(currentCommunicationPoint, communicationStepSize); });
}
fmi2Status fmi2CancelStep(fmi2Component c) {
  return guarded(c, "fmi2CancelStep", [](Instance&) { throw rheo::UsageError("fmi2DoStep never returns fmi2Pending: there is no step to cancel"); });
}

// Statuses of an asynchronous step: there is none (fmi2DoStep returns when the step is done).
// The time of the last successful step and "not terminated" are answered, the rest is fmi2Discard.
fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind, fmi2Status*) { return c ? fmi2Discard : fmi2Error; }
fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real* value) {
  if (!c || !value) return fmi2Error;
  if (s != fmi2LastSuccessfulTime) return fmi2Discard;
  *value = static_cast<Instance*>(c)->cosimulation->time();
  return fmi2OK;
}
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind, fmi2Integer*) { return c ? fmi2Discard : fmi2Error; }
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean* value) {
  if (!c || !value) return fmi2Error;
  if (s != fmi2Terminated) return fmi2Discard;
  *value = fmi2False;
  return fmi2OK;
}
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind, fmi2String*) { return c ? fmi2Discard : fmi2Error; }

}  // extern "C"
