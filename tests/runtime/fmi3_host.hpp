// A minimal FMI 3.0 co-simulation host for the tests: loads an FMU binary with dlopen, resolves
// the standard's functions by name and records what the FMU logs. What an independent host does
// is tested with fmusim (tests/fmusim/).
#pragma once

#include "fmi3Functions.h"

#include <doctest/doctest.h>
#include <dlfcn.h>

#include <string>
#include <vector>

namespace rheo::test {

struct Fmi3Library {
  void* handle = nullptr;
#define RHEO_FMI3_FUNCTION(name) name##TYPE* name = nullptr;
  RHEO_FMI3_FUNCTION(fmi3GetVersion)
  RHEO_FMI3_FUNCTION(fmi3SetDebugLogging)
  RHEO_FMI3_FUNCTION(fmi3InstantiateCoSimulation)
  RHEO_FMI3_FUNCTION(fmi3InstantiateModelExchange)
  RHEO_FMI3_FUNCTION(fmi3FreeInstance)
  RHEO_FMI3_FUNCTION(fmi3EnterInitializationMode)
  RHEO_FMI3_FUNCTION(fmi3ExitInitializationMode)
  RHEO_FMI3_FUNCTION(fmi3EnterEventMode)
  RHEO_FMI3_FUNCTION(fmi3EnterStepMode)
  RHEO_FMI3_FUNCTION(fmi3Terminate)
  RHEO_FMI3_FUNCTION(fmi3Reset)
  RHEO_FMI3_FUNCTION(fmi3GetFloat64)
  RHEO_FMI3_FUNCTION(fmi3SetFloat64)
  RHEO_FMI3_FUNCTION(fmi3GetInt32)
  RHEO_FMI3_FUNCTION(fmi3GetFMUState)
  RHEO_FMI3_FUNCTION(fmi3SetFMUState)
  RHEO_FMI3_FUNCTION(fmi3FreeFMUState)
  RHEO_FMI3_FUNCTION(fmi3SerializedFMUStateSize)
  RHEO_FMI3_FUNCTION(fmi3SerializeFMUState)
  RHEO_FMI3_FUNCTION(fmi3DeserializeFMUState)
  RHEO_FMI3_FUNCTION(fmi3GetDirectionalDerivative)
  RHEO_FMI3_FUNCTION(fmi3SetTime)
  RHEO_FMI3_FUNCTION(fmi3UpdateDiscreteStates)
  RHEO_FMI3_FUNCTION(fmi3DoStep)
#undef RHEO_FMI3_FUNCTION

  explicit Fmi3Library(const std::string& path) {
    handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    REQUIRE_MESSAGE(handle != nullptr, dlerror());
#define RHEO_FMI3_RESOLVE(name)                               \
  name = reinterpret_cast<name##TYPE*>(dlsym(handle, #name)); \
  REQUIRE_MESSAGE(static_cast<bool>(name), #name " is not exported");
    RHEO_FMI3_RESOLVE(fmi3GetVersion)
    RHEO_FMI3_RESOLVE(fmi3SetDebugLogging)
    RHEO_FMI3_RESOLVE(fmi3InstantiateCoSimulation)
    RHEO_FMI3_RESOLVE(fmi3InstantiateModelExchange)
    RHEO_FMI3_RESOLVE(fmi3FreeInstance)
    RHEO_FMI3_RESOLVE(fmi3EnterInitializationMode)
    RHEO_FMI3_RESOLVE(fmi3ExitInitializationMode)
    RHEO_FMI3_RESOLVE(fmi3EnterEventMode)
    RHEO_FMI3_RESOLVE(fmi3EnterStepMode)
    RHEO_FMI3_RESOLVE(fmi3Terminate)
    RHEO_FMI3_RESOLVE(fmi3Reset)
    RHEO_FMI3_RESOLVE(fmi3GetFloat64)
    RHEO_FMI3_RESOLVE(fmi3SetFloat64)
    RHEO_FMI3_RESOLVE(fmi3GetInt32)
    RHEO_FMI3_RESOLVE(fmi3GetFMUState)
    RHEO_FMI3_RESOLVE(fmi3SetFMUState)
    RHEO_FMI3_RESOLVE(fmi3FreeFMUState)
    RHEO_FMI3_RESOLVE(fmi3SerializedFMUStateSize)
    RHEO_FMI3_RESOLVE(fmi3SerializeFMUState)
    RHEO_FMI3_RESOLVE(fmi3DeserializeFMUState)
    RHEO_FMI3_RESOLVE(fmi3GetDirectionalDerivative)
    RHEO_FMI3_RESOLVE(fmi3SetTime)
    RHEO_FMI3_RESOLVE(fmi3UpdateDiscreteStates)
    RHEO_FMI3_RESOLVE(fmi3DoStep)
#undef RHEO_FMI3_RESOLVE
  }
  ~Fmi3Library() {
    if (handle) dlclose(handle);
  }
  Fmi3Library(const Fmi3Library&) = delete;
  Fmi3Library& operator=(const Fmi3Library&) = delete;
};

// What the FMU logged, one entry per call of the logger: "STATUS CATEGORY: MESSAGE".
inline std::vector<std::string>& fmi3_log() {
  static std::vector<std::string> log;
  return log;
}

inline void fmi3_logger(fmi3InstanceEnvironment, fmi3Status status, fmi3String category, fmi3String message) {
  fmi3_log().push_back(std::to_string(static_cast<int>(status)) + " " + category + ": " + message);
}

}  // namespace rheo::test
