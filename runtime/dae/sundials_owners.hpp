// RAII owners of SUNDIALS 6.4 C handles and return-code checking.
//
// Every handle is owned by exactly one object and released in reverse order of creation
// (members are destroyed bottom-up, so declare the context first). Every call that returns a
// flag goes through check(), which turns a failure into a NumericalError naming the call and
// SUNDIALS's own name for the flag (and the last message of the solver's error handler).
#pragma once

#include "runtime/core/errors.hpp"

#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <fmt/format.h>

#include <cstdlib>
#include <memory>
#include <string>

namespace rheo::runtime::sundials {

struct ContextDeleter {
  void operator()(SUNContext ctx) const { SUNContext_Free(&ctx); }
};
struct VectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct MatrixDeleter {
  void operator()(SUNMatrix m) const { SUNMatDestroy(m); }
};
struct LinearSolverDeleter {
  void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); }
};
struct IdaDeleter {
  void operator()(void* mem) const { IDAFree(&mem); }
};

using Context = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter>;
using Vector = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;
using Matrix = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using LinearSolver = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter>;
using IdaMemory = std::unique_ptr<void, IdaDeleter>;

// Throws when a constructor returned null.
template <class Handle>
Handle owned(Handle handle, const char* call) {
  if (!handle) throw NumericalError(fmt::format("SUNDIALS {} failed (out of memory?)", call));
  return handle;
}

// IDA flags: negative is failure. `detail` is the solver's last error message, may be empty.
inline int check_ida(int flag, const char* call, const std::string& detail = {}) {
  if (flag < 0) {
    char* name = IDAGetReturnFlagName(flag);  // malloc'ed by SUNDIALS
    const std::string flag_name = name ? name : std::to_string(flag);
    std::free(name);
    throw NumericalError(fmt::format("SUNDIALS {} failed: {}{}{}", call, flag_name, detail.empty() ? "" : ": ", detail));
  }
  return flag;
}

inline void check_sundials(int flag, const char* call) {
  if (flag != 0) throw NumericalError(fmt::format("SUNDIALS {} failed with code {}", call, flag));
}

}  // namespace rheo::runtime::sundials
