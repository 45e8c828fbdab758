// Error classes of the runtime, each mapped to one documented exit code (docs/cli.md).
// Messages name where (file:row:column, element path, option) and what to do.
#pragma once

#include "lang/model.hpp"

#include <stdexcept>
#include <string>

namespace rheo::runtime {

struct UsageError : std::runtime_error {       // exit 2: the command line is wrong
  using std::runtime_error::runtime_error;
};
struct ModelError : std::invalid_argument {   // exit 3: the model is valid language but cannot be simulated
  using std::invalid_argument::invalid_argument;  // (e.g. an inerter no compliant member holds)
};
struct DataError : std::runtime_error {        // exit 4: a data file or output path is unusable
  using std::runtime_error::runtime_error;
};
struct NumericalError : std::runtime_error {   // exit 5: the numerics could not deliver
  using std::runtime_error::runtime_error;
};

// "file:line:col: error: ", the start of a message about something written at `where`.
inline std::string error_at(const lang::SourceLocation& where) {
  return where.file + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) + ": error: ";
}

namespace exit_code {
inline constexpr int ok = 0;
inline constexpr int internal = 1;
inline constexpr int usage = 2;
inline constexpr int model = 3;
inline constexpr int data = 4;
inline constexpr int numerical = 5;
}  // namespace exit_code

}  // namespace rheo::runtime
