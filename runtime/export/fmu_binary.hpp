// The FMU binary built with this rheo (runtime/fmu/fmi2_entry_points.cpp, fmi3_entry_points.cpp with the front end, the
// network and the fixed-step kernels compiled in; runtime/CMakeLists.txt), carried in rheo's own
// executable: `rheo export` writes it into every FMU, from a build tree or an installed binary
// alike, with nothing to find on disk.
#pragma once

#include <string_view>

namespace rheo::runtime::exporter {

// The bytes of the shared library, an x86-64 Linux ELF that exports the FMI 2.0 and the FMI 3.0
// functions (binaries/linux64/ of an FMI 2.0 FMU, binaries/x86_64-linux/ of an FMI 3.0 one).
std::string_view fmu_binary();

// The platform folders the binary belongs in: FMI 2.0's ("linux64") and FMI 3.0's platform tuple
// ("x86_64-linux", FMI 3.0 section 2.5.1.4).
inline constexpr const char* kFmuPlatform = "linux64";
inline constexpr const char* kFmi3Platform = "x86_64-linux";

}  // namespace rheo::runtime::exporter
