// The FMI 3.0 entry points of an exported FMU's binary, written from the FMI 3.0 specification
// (sections 2.2 and 4): every function fmi3Functions.h declares, with the standard's names and C
// calling convention (third_party/fmi3/fmi3Functions.h declares and exports them; the binary's
// fmi2* functions beside them are another instance type, nothing else is visible). The FMU
// serves co-simulation without event mode (hasEventMode false): after fmi3ExitInitializationMode
// it is in Step Mode, and fmi3DoStep never returns early, asks for no event handling and does
// not end the simulation. The functions of model exchange, scheduled execution, clocks,
// structural parameters, variable dependencies and derivatives are there, as the standard
// requires, and return fmi3Error with a logged message saying what the FMU offers instead.
//
// Each call runs CoSimulation (cosimulation.hpp) under fmu_instance.hpp's guard: a UserError
// becomes fmi3Error with its message logged under category logStatusError, memory exhaustion
// fmi3Fatal. FMI 3.0's logger takes the message as it is (no format string).
#include "fmi3Functions.h"

#include "runtime/core/errors.hpp"
#include "runtime/fmu/cosimulation.hpp"
#include "runtime/fmu/fmu_instance.hpp"
#include "runtime/fmu/fmu_resources.hpp"

#include <fmt/format.h>

#include <cstring>
#include <memory>
#include <string>
#include <utility>

namespace {

using rheo::runtime::fmu::FmiVersion;
using rheo::runtime::fmu::kErrorCategory;
using rheo::runtime::fmu::no_variables_of;
using rheo::runtime::fmu::Outcome;
using rheo::runtime::fmu::require_array;

void log_error(fmi3LogMessageCallback logger, fmi3InstanceEnvironment environment, const std::string& message) {
  if (logger) logger(environment, fmi3Error, kErrorCategory, message.c_str());
}

struct Instance final : rheo::runtime::fmu::FmuInstance {
  using FmuInstance::FmuInstance;
  fmi3InstanceEnvironment environment = nullptr;
  fmi3LogMessageCallback logger = nullptr;
  void log_error(const std::string& message) const override { ::log_error(logger, environment, message); }
};

// Runs BODY on the instance C; fmi3OK, or the status of what it threw, logged.
template <class Body>
fmi3Status guarded(fmi3Instance c, const char* function, Body&& body) {
  if (!c) return fmi3Error;
  switch (rheo::runtime::fmu::guarded(*static_cast<Instance*>(c), function, std::forward<Body>(body))) {
    case Outcome::ok: return fmi3OK;
    case Outcome::fatal: return fmi3Fatal;
    case Outcome::error: break;
  }
  return fmi3Error;
}

// The co-simulation of the instance C (non-null), for the fast paths of the calls a host makes
// every step (cosimulation.hpp), tried before the guard: taken, they cannot fail.
rheo::runtime::fmu::CoSimulation& cosimulation(fmi3Instance c) { return *static_cast<Instance*>(c)->cosimulation; }

// fmi3Error for FUNCTION, which the FMU does not serve: WHY is logged.
fmi3Status unsupported(fmi3Instance c, const char* function, const char* why) {
  return guarded(c, function, [why](Instance&) { throw rheo::UsageError(why); });
}

// The FMU's variables are all scalars: one value per value reference.
void require_scalars(size_t nValueReferences, size_t nValues) {
  if (nValues != nValueReferences)
    throw rheo::UsageError(
        fmt::format("nValues is {} for {} value references; every variable of the FMU is a scalar (one value each)", nValues, nValueReferences));
}

constexpr const char* kCoSimulationOnly = "this FMU is for co-simulation only (fmi3InstantiateCoSimulation); model exchange is not served";
constexpr const char* kNoEventMode =
    "the FMU has no event mode (hasEventMode false): it is in Step Mode from fmi3ExitInitializationMode on; instantiate it with "
    "eventModeUsed false";
constexpr const char* kNoScheduledExecution = "this FMU is for co-simulation only (fmi3InstantiateCoSimulation); scheduled execution is not served";
constexpr const char* kNoStructuralParameters = "the FMU has no structural parameters: there is no configuration mode";
constexpr const char* kNoDerivatives = "the FMU provides no partial derivatives (providesDirectionalDerivatives, providesAdjointDerivatives false)";
constexpr const char* kNoDependencies = "the FMU provides no per-element dependencies (providesPerElementDependencies false)";

}  // namespace

extern "C" {

const char* fmi3GetVersion(void) { return fmi3Version; }

// Errors are logged whatever loggingOn and the categories say, and nothing else ever is: FMI 3.0.3
// section 2.2.4 has an FMU with logging off call logMessage for fmi3Error and fmi3Fatal only,
// which it should log regardless of the settings. The call checks the categories.
fmi3Status fmi3SetDebugLogging(fmi3Instance c, fmi3Boolean /*loggingOn*/, size_t nCategories, const fmi3String categories[]) {
  return guarded(c, "fmi3SetDebugLogging", [&](Instance&) {
    require_array(categories, nCategories, "categories");
    for (size_t k = 0; k < nCategories; ++k)
      if (!categories[k] || std::strcmp(categories[k], kErrorCategory) != 0)
        throw rheo::UsageError(fmt::format("unknown log category '{}'; the FMU logs {}", categories[k] ? categories[k] : "(null)", kErrorCategory));
  });
}

// resourcePath is a native path (FMI 3.0 section 2.2.4), not a URI as in FMI 2.0.
fmi3Instance fmi3InstantiateCoSimulation(fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath, fmi3Boolean /*visible*/,
                                         fmi3Boolean /*loggingOn*/, fmi3Boolean eventModeUsed, fmi3Boolean /*earlyReturnAllowed*/,
                                         const fmi3ValueReference /*requiredIntermediateVariables*/[], size_t /*nRequiredIntermediateVariables*/,
                                         fmi3InstanceEnvironment instanceEnvironment, fmi3LogMessageCallback logMessage,
                                         fmi3IntermediateUpdateCallback /*intermediateUpdate*/) {
  // providesIntermediateUpdate is false: the FMU never calls intermediateUpdate, whatever the host
  // asks for, and never returns early.
  try {
    if (eventModeUsed) throw rheo::UsageError(kNoEventMode);
    if (!instantiationToken) throw rheo::UsageError("instantiationToken is NULL; pass the instantiationToken of modelDescription.xml");
    if (!resourcePath || !*resourcePath) throw rheo::UsageError("resourcePath is NULL; the FMU reads its model from its resources folder");
    auto instance = std::make_unique<Instance>(instanceName ? instanceName : "");
    instance->environment = instanceEnvironment;
    instance->logger = logMessage;
    instance->cosimulation = rheo::runtime::fmu::load_cosimulation(resourcePath, instantiationToken, RHEO_VERSION, FmiVersion::fmi3);
    return instance.release();
  } catch (const rheo::UserError& e) {
    log_error(logMessage, instanceEnvironment, fmt::format("fmi3InstantiateCoSimulation: {}", e.what()));
  } catch (const std::exception& e) {
    log_error(logMessage, instanceEnvironment,
              fmt::format("fmi3InstantiateCoSimulation: internal error: {}; please report it to rheo with the FMU", e.what()));
  }
  return nullptr;
}

fmi3Instance fmi3InstantiateModelExchange(fmi3String /*instanceName*/, fmi3String /*instantiationToken*/, fmi3String /*resourcePath*/,
                                          fmi3Boolean /*visible*/, fmi3Boolean /*loggingOn*/, fmi3InstanceEnvironment instanceEnvironment,
                                          fmi3LogMessageCallback logMessage) {
  log_error(logMessage, instanceEnvironment, fmt::format("fmi3InstantiateModelExchange: {}", kCoSimulationOnly));
  return nullptr;
}

fmi3Instance fmi3InstantiateScheduledExecution(fmi3String /*instanceName*/, fmi3String /*instantiationToken*/, fmi3String /*resourcePath*/,
                                               fmi3Boolean /*visible*/, fmi3Boolean /*loggingOn*/, fmi3InstanceEnvironment instanceEnvironment,
                                               fmi3LogMessageCallback logMessage, fmi3ClockUpdateCallback /*clockUpdate*/,
                                               fmi3LockPreemptionCallback /*lockPreemption*/, fmi3UnlockPreemptionCallback /*unlockPreemption*/) {
  log_error(logMessage, instanceEnvironment, fmt::format("fmi3InstantiateScheduledExecution: {}", kNoScheduledExecution));
  return nullptr;
}

void fmi3FreeInstance(fmi3Instance c) { delete static_cast<Instance*>(c); }

// The kernels are exact for the input path: a tolerance changes nothing.
fmi3Status fmi3EnterInitializationMode(fmi3Instance c, fmi3Boolean /*toleranceDefined*/, fmi3Float64 /*tolerance*/, fmi3Float64 startTime,
                                       fmi3Boolean stopTimeDefined, fmi3Float64 stopTime) {
  return guarded(c, "fmi3EnterInitializationMode", [&](Instance& i) {
    i.cosimulation->enter_initialization(startTime, stopTimeDefined ? std::optional<double>(stopTime) : std::nullopt);
  });
}
fmi3Status fmi3ExitInitializationMode(fmi3Instance c) {
  return guarded(c, "fmi3ExitInitializationMode", [](Instance& i) { i.cosimulation->exit_initialization(); });
}
fmi3Status fmi3EnterEventMode(fmi3Instance c) { return unsupported(c, "fmi3EnterEventMode", kNoEventMode); }
// Super state Initialized (FMI 3.0 section 2.3.4), of which this FMU has Step Mode only.
fmi3Status fmi3Terminate(fmi3Instance c) {
  return guarded(c, "fmi3Terminate", [](Instance& i) { i.cosimulation->terminate(); });
}
fmi3Status fmi3Reset(fmi3Instance c) {
  return guarded(c, "fmi3Reset", [](Instance& i) { i.cosimulation->reset(); });
}

fmi3Status fmi3GetFloat64(fmi3Instance c, const fmi3ValueReference valueReferences[], size_t nValueReferences, fmi3Float64 values[], size_t nValues) {
  if (c && nValueReferences == 1 && nValues == 1 && valueReferences && values && cosimulation(c).get_output_fast(valueReferences[0], values[0]))
    return fmi3OK;
  return guarded(c, "fmi3GetFloat64", [&](Instance& i) {
    require_scalars(nValueReferences, nValues);
    require_array(valueReferences, nValueReferences, "valueReferences");
    require_array(values, nValues, "values");
    for (size_t k = 0; k < nValueReferences; ++k) values[k] = i.cosimulation->get_real(valueReferences[k]);
  });
}
fmi3Status fmi3SetFloat64(fmi3Instance c, const fmi3ValueReference valueReferences[], size_t nValueReferences, const fmi3Float64 values[],
                          size_t nValues) {
  // u, or u and v: what a host sets every step. Where one of them is not taken fast, the guarded
  // call sets them all again and names what is wrong.
  if (c && nValueReferences == nValues && (nValues == 1 || nValues == 2) && valueReferences && values) {
    auto& cosimulation_c = cosimulation(c);
    bool taken = cosimulation_c.set_input_fast(valueReferences[0], values[0]);
    if (taken && nValues == 2) taken = cosimulation_c.set_input_fast(valueReferences[1], values[1]);
    if (taken) return fmi3OK;
  }
  return guarded(c, "fmi3SetFloat64", [&](Instance& i) {
    require_scalars(nValueReferences, nValues);
    require_array(valueReferences, nValueReferences, "valueReferences");
    require_array(values, nValues, "values");
    for (size_t k = 0; k < nValueReferences; ++k) i.cosimulation->set_real(valueReferences[k], values[k]);
  });
}

// Every variable is a Float64: getters and setters of the other types take no value references.
#define RHEO_FMI3_NO_VARIABLES(type, text)                                                                                    \
  fmi3Status fmi3Get##type(fmi3Instance c, const fmi3ValueReference[], size_t nValueReferences, fmi3##type[], size_t) {       \
    return guarded(c, "fmi3Get" #type, [&](Instance&) { no_variables_of(text, nValueReferences); });                          \
  }                                                                                                                           \
  fmi3Status fmi3Set##type(fmi3Instance c, const fmi3ValueReference[], size_t nValueReferences, const fmi3##type[], size_t) { \
    return guarded(c, "fmi3Set" #type, [&](Instance&) { no_variables_of(text, nValueReferences); });                          \
  }
RHEO_FMI3_NO_VARIABLES(Float32, "Float32")
RHEO_FMI3_NO_VARIABLES(Int8, "Int8")
RHEO_FMI3_NO_VARIABLES(UInt8, "UInt8")
RHEO_FMI3_NO_VARIABLES(Int16, "Int16")
RHEO_FMI3_NO_VARIABLES(UInt16, "UInt16")
RHEO_FMI3_NO_VARIABLES(Int32, "Int32")
RHEO_FMI3_NO_VARIABLES(UInt32, "UInt32")
RHEO_FMI3_NO_VARIABLES(Int64, "Int64 or Enumeration")
RHEO_FMI3_NO_VARIABLES(UInt64, "UInt64")
RHEO_FMI3_NO_VARIABLES(Boolean, "Boolean")
RHEO_FMI3_NO_VARIABLES(String, "String")
#undef RHEO_FMI3_NO_VARIABLES

fmi3Status fmi3GetBinary(fmi3Instance c, const fmi3ValueReference[], size_t nValueReferences, size_t[], fmi3Binary[], size_t) {
  return guarded(c, "fmi3GetBinary", [&](Instance&) { no_variables_of("Binary", nValueReferences); });
}
fmi3Status fmi3SetBinary(fmi3Instance c, const fmi3ValueReference[], size_t nValueReferences, const size_t[], const fmi3Binary[], size_t) {
  return guarded(c, "fmi3SetBinary", [&](Instance&) { no_variables_of("Binary", nValueReferences); });
}
fmi3Status fmi3GetClock(fmi3Instance c, const fmi3ValueReference[], size_t nValueReferences, fmi3Clock[]) {
  return guarded(c, "fmi3GetClock", [&](Instance&) { no_variables_of("Clock", nValueReferences); });
}
fmi3Status fmi3SetClock(fmi3Instance c, const fmi3ValueReference[], size_t nValueReferences, const fmi3Clock[]) {
  return guarded(c, "fmi3SetClock", [&](Instance&) { no_variables_of("Clock", nValueReferences); });
}

fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance c, fmi3ValueReference, size_t*) {
  return unsupported(c, "fmi3GetNumberOfVariableDependencies", kNoDependencies);
}
fmi3Status fmi3GetVariableDependencies(fmi3Instance c, fmi3ValueReference, size_t[], fmi3ValueReference[], size_t[], fmi3DependencyKind[], size_t) {
  return unsupported(c, "fmi3GetVariableDependencies", kNoDependencies);
}

// FMU states: FmuInstance's, handed to the host until it frees them (or frees the instance).
fmi3Status fmi3GetFMUState(fmi3Instance c, fmi3FMUState* FMUState) {
  return guarded(c, "fmi3GetFMUState", [&](Instance& i) {
    require_array(FMUState, 1, "FMUState");
    if (*FMUState) i.state(*FMUState) = i.cosimulation->snapshot();
    else *FMUState = i.new_state(i.cosimulation->snapshot());
  });
}
fmi3Status fmi3SetFMUState(fmi3Instance c, fmi3FMUState FMUState) {
  return guarded(c, "fmi3SetFMUState", [&](Instance& i) { i.cosimulation->restore(i.state(FMUState)); });
}
fmi3Status fmi3FreeFMUState(fmi3Instance c, fmi3FMUState* FMUState) {
  return guarded(c, "fmi3FreeFMUState", [&](Instance& i) { i.free_state(FMUState); });
}
fmi3Status fmi3SerializedFMUStateSize(fmi3Instance c, fmi3FMUState FMUState, size_t* size) {
  return guarded(c, "fmi3SerializedFMUStateSize", [&](Instance& i) {
    require_array(size, 1, "size");
    *size = i.cosimulation->serialize(i.state(FMUState)).size();
  });
}
fmi3Status fmi3SerializeFMUState(fmi3Instance c, fmi3FMUState FMUState, fmi3Byte serializedState[], size_t size) {
  return guarded(c, "fmi3SerializeFMUState", [&](Instance& i) {
    const std::string bytes = i.cosimulation->serialize(i.state(FMUState));
    if (size < bytes.size())
      throw rheo::UsageError(fmt::format("the buffer holds {} bytes; the state needs {} (fmi3SerializedFMUStateSize)", size, bytes.size()));
    require_array(serializedState, bytes.size(), "serializedState");
    std::memcpy(serializedState, bytes.data(), bytes.size());
  });
}
// Always a new state: the standard has the FMU construct one, whatever *FMUState holds on entry.
fmi3Status fmi3DeserializeFMUState(fmi3Instance c, const fmi3Byte serializedState[], size_t size, fmi3FMUState* FMUState) {
  return guarded(c, "fmi3DeserializeFMUState", [&](Instance& i) {
    require_array(serializedState, size, "serializedState");
    require_array(FMUState, 1, "FMUState");
    const std::string_view bytes(reinterpret_cast<const char*>(serializedState), size);
    *FMUState = i.new_state(i.cosimulation->deserialize(bytes));
  });
}

fmi3Status fmi3GetDirectionalDerivative(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3ValueReference[], size_t, const fmi3Float64[],
                                        size_t, fmi3Float64[], size_t) {
  return unsupported(c, "fmi3GetDirectionalDerivative", kNoDerivatives);
}
fmi3Status fmi3GetAdjointDerivative(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3ValueReference[], size_t, const fmi3Float64[],
                                    size_t, fmi3Float64[], size_t) {
  return unsupported(c, "fmi3GetAdjointDerivative", kNoDerivatives);
}

fmi3Status fmi3EnterConfigurationMode(fmi3Instance c) { return unsupported(c, "fmi3EnterConfigurationMode", kNoStructuralParameters); }
fmi3Status fmi3ExitConfigurationMode(fmi3Instance c) { return unsupported(c, "fmi3ExitConfigurationMode", kNoStructuralParameters); }

// Clocks: the FMU has none.
fmi3Status fmi3GetIntervalDecimal(fmi3Instance c, const fmi3ValueReference[], size_t n, fmi3Float64[], fmi3IntervalQualifier[]) {
  return guarded(c, "fmi3GetIntervalDecimal", [&](Instance&) { no_variables_of("Clock", n); });
}
fmi3Status fmi3GetIntervalFraction(fmi3Instance c, const fmi3ValueReference[], size_t n, fmi3UInt64[], fmi3UInt64[], fmi3IntervalQualifier[]) {
  return guarded(c, "fmi3GetIntervalFraction", [&](Instance&) { no_variables_of("Clock", n); });
}
fmi3Status fmi3GetShiftDecimal(fmi3Instance c, const fmi3ValueReference[], size_t n, fmi3Float64[]) {
  return guarded(c, "fmi3GetShiftDecimal", [&](Instance&) { no_variables_of("Clock", n); });
}
fmi3Status fmi3GetShiftFraction(fmi3Instance c, const fmi3ValueReference[], size_t n, fmi3UInt64[], fmi3UInt64[]) {
  return guarded(c, "fmi3GetShiftFraction", [&](Instance&) { no_variables_of("Clock", n); });
}
fmi3Status fmi3SetIntervalDecimal(fmi3Instance c, const fmi3ValueReference[], size_t n, const fmi3Float64[]) {
  return guarded(c, "fmi3SetIntervalDecimal", [&](Instance&) { no_variables_of("Clock", n); });
}
fmi3Status fmi3SetIntervalFraction(fmi3Instance c, const fmi3ValueReference[], size_t n, const fmi3UInt64[], const fmi3UInt64[]) {
  return guarded(c, "fmi3SetIntervalFraction", [&](Instance&) { no_variables_of("Clock", n); });
}
fmi3Status fmi3SetShiftDecimal(fmi3Instance c, const fmi3ValueReference[], size_t n, const fmi3Float64[]) {
  return guarded(c, "fmi3SetShiftDecimal", [&](Instance&) { no_variables_of("Clock", n); });
}
fmi3Status fmi3SetShiftFraction(fmi3Instance c, const fmi3ValueReference[], size_t n, const fmi3UInt64[], const fmi3UInt64[]) {
  return guarded(c, "fmi3SetShiftFraction", [&](Instance&) { no_variables_of("Clock", n); });
}

fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance c) { return unsupported(c, "fmi3EvaluateDiscreteStates", kNoEventMode); }
fmi3Status fmi3UpdateDiscreteStates(fmi3Instance c, fmi3Boolean*, fmi3Boolean*, fmi3Boolean*, fmi3Boolean*, fmi3Boolean*, fmi3Float64*) {
  return unsupported(c, "fmi3UpdateDiscreteStates", kNoEventMode);
}

// Model exchange: not served.
fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance c) { return unsupported(c, "fmi3EnterContinuousTimeMode", kCoSimulationOnly); }
fmi3Status fmi3CompletedIntegratorStep(fmi3Instance c, fmi3Boolean, fmi3Boolean*, fmi3Boolean*) {
  return unsupported(c, "fmi3CompletedIntegratorStep", kCoSimulationOnly);
}
fmi3Status fmi3SetTime(fmi3Instance c, fmi3Float64) { return unsupported(c, "fmi3SetTime", kCoSimulationOnly); }
fmi3Status fmi3SetContinuousStates(fmi3Instance c, const fmi3Float64[], size_t) {
  return unsupported(c, "fmi3SetContinuousStates", kCoSimulationOnly);
}
fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance c, fmi3Float64[], size_t) {
  return unsupported(c, "fmi3GetContinuousStateDerivatives", kCoSimulationOnly);
}
fmi3Status fmi3GetEventIndicators(fmi3Instance c, fmi3Float64[], size_t) { return unsupported(c, "fmi3GetEventIndicators", kCoSimulationOnly); }
fmi3Status fmi3GetContinuousStates(fmi3Instance c, fmi3Float64[], size_t) { return unsupported(c, "fmi3GetContinuousStates", kCoSimulationOnly); }
fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance c, fmi3Float64[], size_t) {
  return unsupported(c, "fmi3GetNominalsOfContinuousStates", kCoSimulationOnly);
}
fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance c, size_t*) { return unsupported(c, "fmi3GetNumberOfEventIndicators", kCoSimulationOnly); }
fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance c, size_t*) { return unsupported(c, "fmi3GetNumberOfContinuousStates", kCoSimulationOnly); }

// Co-simulation.
fmi3Status fmi3EnterStepMode(fmi3Instance c) { return unsupported(c, "fmi3EnterStepMode", kNoEventMode); }
fmi3Status fmi3GetOutputDerivatives(fmi3Instance c, const fmi3ValueReference[], size_t nValueReferences, const fmi3Int32[], fmi3Float64[], size_t) {
  return guarded(c, "fmi3GetOutputDerivatives", [&](Instance&) {
    if (nValueReferences > 0) throw rheo::UsageError("the FMU provides no output derivatives (maxOutputDerivativeOrder 0)");
  });
}
// The step either is taken whole (lastSuccessfulTime its end) or fails with nothing changed.
fmi3Status fmi3DoStep(fmi3Instance c, fmi3Float64 currentCommunicationPoint, fmi3Float64 communicationStepSize,
                      fmi3Boolean /*noSetFMUStatePriorToCurrentPoint*/, fmi3Boolean* eventHandlingNeeded, fmi3Boolean* terminateSimulation,
                      fmi3Boolean* earlyReturn, fmi3Float64* lastSuccessfulTime) {
  return guarded(c, "fmi3DoStep", [&](Instance& i) {
    if (!eventHandlingNeeded || !terminateSimulation || !earlyReturn || !lastSuccessfulTime)
      throw rheo::UsageError("an output argument (eventHandlingNeeded, terminateSimulation, earlyReturn, lastSuccessfulTime) is NULL");
    i.cosimulation->do_step(currentCommunicationPoint, communicationStepSize);
    *eventHandlingNeeded = fmi3False;
    *terminateSimulation = fmi3False;
    *earlyReturn = fmi3False;
    *lastSuccessfulTime = i.cosimulation->time();
  });
}

// Scheduled execution: not served.
fmi3Status fmi3ActivateModelPartition(fmi3Instance c, fmi3ValueReference, fmi3Float64) {
  return unsupported(c, "fmi3ActivateModelPartition", kNoScheduledExecution);
}

}  // extern "C"
