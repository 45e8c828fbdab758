#include "runtime/export/fmu_binary.hpp"

#include <cstddef>

// Defined by the object runtime/CMakeLists.txt makes of the shared library with
// `ld -r -b binary` (its first byte and one past its last).
extern "C" const char rheo_fmu_binary_start[];
extern "C" const char rheo_fmu_binary_end[];

namespace rheo::runtime::exporter {

std::string_view fmu_binary() { return {rheo_fmu_binary_start, static_cast<std::size_t>(rheo_fmu_binary_end - rheo_fmu_binary_start)}; }

}  // namespace rheo::runtime::exporter
