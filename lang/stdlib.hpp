// Lookup of the embedded standard library (stdlib/*.rheo) by `import NAME`.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rheo::lang {

// The source text of module NAME, or nullopt when there is none.
std::optional<std::string_view> stdlib_source(std::string_view name);
// Every module name, sorted.
std::vector<std::string> stdlib_names();
// "<stdlib>/NAME.rheo": the file name diagnostics use for the module.
std::string stdlib_path(std::string_view name);

}  // namespace rheo::lang
