// What a fuzz target may see: the errors rheo reports with a documented exit code (docs/cli.md:
// CompileError and ModelError 3, UsageError 2, DataError 4, NumericalError 5) are the expected
// answer to hostile input. Anything else that escapes (what `rheo` would call an internal error,
// exit 1) prints its message and aborts, which libFuzzer reports as a crash with the input.
#pragma once

#include "lang/diagnostics.hpp"
#include "runtime/core/errors.hpp"

#include <cstdio>
#include <cstdlib>
#include <exception>

namespace rheo::fuzz {

template <class Body>
void expect_only_documented_errors(Body&& body) {
  try {
    body();
  } catch (const UserError&) {  // lang/errors.hpp
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rheo fuzz: undocumented exception (an internal error): %s\n", e.what());
    std::abort();
  }
}

}  // namespace rheo::fuzz
