// A minimal FMI 2.0 co-simulation host for the tests: loads an FMU binary with dlopen, resolves
// the standard's functions by name and records what the FMU logs. What an independent host does
// is tested with fmusim (tests/fmusim/).
#pragma once

#include "fmi2Functions.h"

#include <doctest/doctest.h>
#include <dlfcn.h>

#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace rheo::test {

struct Fmi2Library {
  void* handle = nullptr;
#define RHEO_FMI2_FUNCTION(name) name##TYPE* name = nullptr;
  RHEO_FMI2_FUNCTION(fmi2GetVersion)
  RHEO_FMI2_FUNCTION(fmi2GetTypesPlatform)
  RHEO_FMI2_FUNCTION(fmi2SetDebugLogging)
  RHEO_FMI2_FUNCTION(fmi2Instantiate)
  RHEO_FMI2_FUNCTION(fmi2FreeInstance)
  RHEO_FMI2_FUNCTION(fmi2SetupExperiment)
  RHEO_FMI2_FUNCTION(fmi2EnterInitializationMode)
  RHEO_FMI2_FUNCTION(fmi2ExitInitializationMode)
  RHEO_FMI2_FUNCTION(fmi2Terminate)
  RHEO_FMI2_FUNCTION(fmi2Reset)
  RHEO_FMI2_FUNCTION(fmi2GetReal)
  RHEO_FMI2_FUNCTION(fmi2SetReal)
  RHEO_FMI2_FUNCTION(fmi2GetInteger)
  RHEO_FMI2_FUNCTION(fmi2GetFMUstate)
  RHEO_FMI2_FUNCTION(fmi2SetFMUstate)
  RHEO_FMI2_FUNCTION(fmi2FreeFMUstate)
  RHEO_FMI2_FUNCTION(fmi2SerializedFMUstateSize)
  RHEO_FMI2_FUNCTION(fmi2SerializeFMUstate)
  RHEO_FMI2_FUNCTION(fmi2DeSerializeFMUstate)
  RHEO_FMI2_FUNCTION(fmi2SetRealInputDerivatives)
  RHEO_FMI2_FUNCTION(fmi2DoStep)
  RHEO_FMI2_FUNCTION(fmi2GetRealStatus)
#undef RHEO_FMI2_FUNCTION

  explicit Fmi2Library(const std::string& path) {
    handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    REQUIRE_MESSAGE(handle != nullptr, dlerror());
#define RHEO_FMI2_RESOLVE(name)                               \
  name = reinterpret_cast<name##TYPE*>(dlsym(handle, #name)); \
  REQUIRE_MESSAGE(static_cast<bool>(name), #name " is not exported");
    RHEO_FMI2_RESOLVE(fmi2GetVersion)
    RHEO_FMI2_RESOLVE(fmi2GetTypesPlatform)
    RHEO_FMI2_RESOLVE(fmi2SetDebugLogging)
    RHEO_FMI2_RESOLVE(fmi2Instantiate)
    RHEO_FMI2_RESOLVE(fmi2FreeInstance)
    RHEO_FMI2_RESOLVE(fmi2SetupExperiment)
    RHEO_FMI2_RESOLVE(fmi2EnterInitializationMode)
    RHEO_FMI2_RESOLVE(fmi2ExitInitializationMode)
    RHEO_FMI2_RESOLVE(fmi2Terminate)
    RHEO_FMI2_RESOLVE(fmi2Reset)
    RHEO_FMI2_RESOLVE(fmi2GetReal)
    RHEO_FMI2_RESOLVE(fmi2SetReal)
    RHEO_FMI2_RESOLVE(fmi2GetInteger)
    RHEO_FMI2_RESOLVE(fmi2GetFMUstate)
    RHEO_FMI2_RESOLVE(fmi2SetFMUstate)
    RHEO_FMI2_RESOLVE(fmi2FreeFMUstate)
    RHEO_FMI2_RESOLVE(fmi2SerializedFMUstateSize)
    RHEO_FMI2_RESOLVE(fmi2SerializeFMUstate)
    RHEO_FMI2_RESOLVE(fmi2DeSerializeFMUstate)
    RHEO_FMI2_RESOLVE(fmi2SetRealInputDerivatives)
    RHEO_FMI2_RESOLVE(fmi2DoStep)
    RHEO_FMI2_RESOLVE(fmi2GetRealStatus)
#undef RHEO_FMI2_RESOLVE
  }
  ~Fmi2Library() {
    if (handle) dlclose(handle);
  }
  Fmi2Library(const Fmi2Library&) = delete;
  Fmi2Library& operator=(const Fmi2Library&) = delete;
};

// What the FMU logged, one entry per call of the logger: "STATUS CATEGORY: MESSAGE" (formatted).
inline std::vector<std::string>& fmi2_log() {
  static std::vector<std::string> log;
  return log;
}

inline void fmi2_logger(fmi2ComponentEnvironment, fmi2String, fmi2Status status, fmi2String category, fmi2String message, ...) {
  char text[4096];
  va_list args;
  va_start(args, message);
  std::vsnprintf(text, sizeof text, message, args);
  va_end(args);
  fmi2_log().push_back(std::to_string(static_cast<int>(status)) + " " + category + ": " + text);
}

inline const fmi2CallbackFunctions* fmi2_callbacks() {
  static const fmi2CallbackFunctions callbacks{fmi2_logger, std::calloc, std::free, nullptr, nullptr};
  return &callbacks;
}

}  // namespace rheo::test
