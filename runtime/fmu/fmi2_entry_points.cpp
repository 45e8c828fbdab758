// The FMI 2.0 co-simulation entry points of an exported FMU's binary, written from the FMI 2.0.4
// specification (sections 2.1 and 4): the common functions and those of co-simulation, with the
// standard's names and C calling convention (third_party/fmi2/fmi2Functions.h declares them and
// exports them from the shared library; nothing else of the binary is visible).
//
// Each call runs CoSimulation (cosimulation.hpp) and never lets an exception reach the host: a
// UserError becomes fmi2Error with its message logged under category logStatusError (always, as
// the standard asks of errors), anything else fmi2Error with "internal error" in front, memory
// exhaustion fmi2Fatal. A call that fails changes nothing, so a host may restore a saved FMU state
// (fmi2SetFMUstate) and go on. Messages are escaped for the logger's printf-style format ('%' as
// "%%") and the standard's variable references ('#' as "##").
#include "fmi2Functions.h"

#include "runtime/core/errors.hpp"
#include "runtime/fmu/cosimulation.hpp"
#include "runtime/fmu/fmu_resources.hpp"

#include <fmt/format.h>

#include <cstring>
#include <memory>
#include <new>
#include <set>
#include <string>

namespace __gnu_cxx {
void __freeres();  // libstdc++'s own (what valgrind calls at exit); no header declares it
}

namespace {

// libstdc++, linked in statically, allocates a 72 KB arena for exceptions thrown when memory runs
// out (its emergency pool) when the library is loaded. Freed when the host unloads the FMU, so
// that loading and unloading it does not lose the arena each time.
[[gnu::destructor]] void free_exception_pool() { __gnu_cxx::__freeres(); }

using rheo::runtime::fmu::CoSimulation;
using rheo::runtime::fmu::Snapshot;

constexpr const char* kErrorCategory = "logStatusError";

struct Instance {
  std::string name;
  fmi2CallbackFunctions callbacks{};
  std::unique_ptr<CoSimulation> cosimulation;
  // The FMU states handed to the host and not yet freed: a state passed back is checked against
  // them, so that a stale or foreign pointer is an error, not a crash. Freed with the instance.
  std::set<Snapshot*> states;

  ~Instance() {
    for (Snapshot* s : states) delete s;
  }
  Snapshot* new_state(Snapshot s) {
    auto owned = std::make_unique<Snapshot>(std::move(s));
    states.insert(owned.get());
    return owned.release();
  }
  Snapshot& state(fmi2FMUstate handle) {
    const auto found = states.find(static_cast<Snapshot*>(handle));
    if (found == states.end()) throw rheo::UsageError("FMUstate is not a state this instance gave out, or was freed");
    return **found;
  }
};

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

void log_error(const Instance& i, const std::string& message) {
  log_error(i.callbacks.logger, i.callbacks.componentEnvironment, i.name.c_str(), message);
}

// Runs BODY on the instance C; fmi2OK, or the status of what it threw, logged.
template <class Body>
fmi2Status guarded(fmi2Component c, const char* function, Body&& body) {
  if (!c) return fmi2Error;
  Instance& i = *static_cast<Instance*>(c);
  try {
    body(i);
    return fmi2OK;
  } catch (const rheo::UserError& e) {
    log_error(i, fmt::format("{}: {}", function, e.what()));
  } catch (const std::bad_alloc&) {
    log_error(i, fmt::format("{}: out of memory", function));
    return fmi2Fatal;
  } catch (const std::exception& e) {
    log_error(i, fmt::format("{}: internal error: {}; please report it to rheo with the FMU", function, e.what()));
  }
  return fmi2Error;
}

[[noreturn, gnu::noinline, gnu::cold]] void null_array(const char* what, size_t n) {
  throw rheo::UsageError(fmt::format("{} is NULL for {} values", what, n));
}

// ARRAY, of N elements, may be null only when N is 0.
template <class T>
void require_array(const T* array, size_t n, const char* what) {
  if (n > 0 && array == nullptr) null_array(what, n);
}

void no_variables_of(const char* type, size_t n) {
  if (n > 0) throw rheo::UsageError(fmt::format("the FMU has no {} variables ({} value references given)", type, n));
}

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
    auto instance = std::make_unique<Instance>();
    instance->name = name;
    if (functions) instance->callbacks = *functions;
    instance->cosimulation = rheo::runtime::fmu::load_cosimulation(rheo::runtime::fmu::resource_folder(fmuResourceLocation), fmuGUID, RHEO_VERSION);
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

// FMU states: Snapshots on the heap, owned by the instance, handed to the host until it frees
// them (or frees the instance).
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
// FMUstate is the address of the host's handle. A host that passes the handle itself (fmusim
// 31d7d40 does, restoring a state from a file) gets it freed all the same: a handle is one of
// the instance's states, which no host's variable is, so the two cannot be confused.
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate* FMUstate) {
  return guarded(c, "fmi2FreeFMUstate", [&](Instance& i) {
    if (!FMUstate) return;
    auto* handle = static_cast<Snapshot*>(static_cast<void*>(FMUstate));
    const bool passed_itself = i.states.count(handle) > 0;
    if (!passed_itself && !*FMUstate) return;
    if (!passed_itself) handle = &i.state(*FMUstate);
    i.states.erase(handle);
    delete handle;
    if (!passed_itself) *FMUstate = nullptr;
  });
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
