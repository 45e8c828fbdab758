// The FMU binary built with this rheo (runtime/fmu/fmi2_entry_points.cpp with the front end, the
// network and the fixed-step kernels compiled in; runtime/CMakeLists.txt), carried in rheo's own
// executable: `rheo export` writes it into every FMU, from a build tree or an installed binary
// alike, with nothing to find on disk.
#pragma once

#include <string_view>

namespace rheo::runtime::exporter {

// The bytes of the shared library, an x86-64 Linux ELF (binaries/linux64/ of an FMU).
std::string_view fmu_binary();

// The FMI platform folder the binary belongs in ("linux64").
inline constexpr const char* kFmuPlatform = "linux64";

}  // namespace rheo::runtime::exporter
