// Syntax tree -> checked Program (model.hpp). Reports every semantic error it finds.
#pragma once

#include "lang/ast.hpp"
#include "lang/diagnostics.hpp"

#include <vector>

namespace rheo::lang {

// FILE is the main file; IMPORTED are the parsed modules its imports name (their models join
// the Program first, in import order). Errors go to ERRORS; the Program is complete only when
// no error was added.
Program check(const ast::File& file, const std::vector<const ast::File*>& imported, std::vector<Diagnostic>& errors);

}  // namespace rheo::lang
