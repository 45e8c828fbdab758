// The standard library of models (stdlib/*.rheo), embedded at build time.
#pragma once

#include <string_view>
#include <vector>

namespace rheo::stdlib {

struct Module {
  std::string_view name;  // file name without .rheo: `import NAME`
  std::string_view text;  // the file's contents
};

// Every module, sorted by name.
const std::vector<Module>& modules();

}  // namespace rheo::stdlib
