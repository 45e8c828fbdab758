// The runtime's names for the error classes of lang/errors.hpp (one exit code each,
// docs/cli.md), and the location prefix of their messages.
#pragma once

#include "lang/errors.hpp"
#include "lang/model.hpp"

#include <string>

namespace rheo::runtime {

using rheo::DataError;
using rheo::ModelError;
using rheo::NumericalError;
using rheo::UsageError;
using rheo::UserError;
namespace exit_code = rheo::exit_code;

// "file:line:col: error: ", the start of a message about something written at `where`.
inline std::string error_at(const lang::SourceLocation& where) {
  return where.file + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) + ": error: ";
}

}  // namespace rheo::runtime
