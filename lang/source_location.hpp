// Where something is written in a source file: what every user-facing error names.
#pragma once

#include <string>

namespace rheo::lang {

struct SourceLocation {
  std::string file;  // as given on the command line, or "<stdlib>/NAME.rheo"
  int line = 0;      // 1-based
  int column = 0;    // 1-based, in bytes
};

}  // namespace rheo::lang
