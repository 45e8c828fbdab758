// What the FMU binary's entry points of both FMI versions share (fmi2_entry_points.cpp,
// fmi3_entry_points.cpp): one instance as a host holds it, with the FMU states it handed out, and
// the guard that turns whatever a call throws into a status and a logged message, so that no
// exception reaches the host.
//
// A call that fails changes nothing (CoSimulation's contract), so a host may restore a saved FMU
// state and go on. Errors are logged whatever the host's logging switch says, as both standards
// ask of errors (FMI 2.0: the logger was called for every fmi2Error; FMI 3.0.3 section 2.2.4:
// regardless of the logging settings), under the one category the FMU declares (kErrorCategory),
// and nothing else is logged.
#pragma once

#include "runtime/core/errors.hpp"
#include "runtime/fmu/cosimulation.hpp"

#include <fmt/format.h>

#include <cstddef>
#include <exception>
#include <memory>
#include <new>
#include <set>
#include <string>

namespace rheo::runtime::fmu {

inline constexpr const char* kErrorCategory = "logStatusError";

// How a guarded call ended: fmi2OK/fmi3OK, fmi*Error, fmi*Fatal.
enum class Outcome { ok, error, fatal };

class FmuInstance {
 public:
  explicit FmuInstance(std::string name) : name_(std::move(name)) {}
  virtual ~FmuInstance();
  FmuInstance(const FmuInstance&) = delete;
  FmuInstance& operator=(const FmuInstance&) = delete;

  const std::string& name() const { return name_; }

  // MESSAGE to the host's logger, as an error under kErrorCategory (nothing without a logger).
  virtual void log_error(const std::string& message) const = 0;

  // FMU states: Snapshots on the heap, owned by the instance, handed to the host as opaque
  // handles until it frees them (or frees the instance).
  void* new_state(Snapshot s);
  // The state HANDLE stands for; UsageError for a handle this instance did not give out, or freed,
  // so that a stale or foreign pointer is an error, not a crash.
  Snapshot& state(void* handle);
  // Frees the state whose handle *ADDRESS holds and sets the handle to null (null: nothing to
  // free). A host that passes the handle itself instead of its address (fmusim 31d7d40 does,
  // restoring a state from a file) gets it freed all the same: a handle is one of the instance's
  // states, which no host's variable is, so the two cannot be confused.
  void free_state(void** address);

  std::unique_ptr<CoSimulation> cosimulation;

 private:
  std::string name_;
  std::set<Snapshot*> states_;
};

[[noreturn]] void null_array(const char* what, std::size_t n);

// UsageError unless ARRAY, of N elements, is non-null or N is 0.
template <class T>
void require_array(const T* array, std::size_t n, const char* what) {
  if (n > 0 && array == nullptr) null_array(what, n);
}

// UsageError for N > 0 value references of TYPE ("Integer", "Int32"), which the FMU has none of.
void no_variables_of(const char* type, std::size_t n);

// Runs BODY(INSTANCE); a UserError it throws is logged as "FUNCTION: message" and is an error,
// memory exhaustion is fatal, any other exception an error logged as an internal one.
template <class Instance, class Body>
Outcome guarded(Instance& instance, const char* function, Body&& body) noexcept {
  try {
    try {
      body(instance);
      return Outcome::ok;
    } catch (const UserError& e) {
      instance.log_error(fmt::format("{}: {}", function, e.what()));
    } catch (const std::bad_alloc&) {
      instance.log_error(fmt::format("{}: out of memory", function));
      return Outcome::fatal;
    } catch (const std::exception& e) {
      instance.log_error(fmt::format("{}: internal error: {}; please report it to rheo with the FMU", function, e.what()));
    }
  } catch (...) {  // the message could not be formatted (memory): the host learns the status only
  }
  return Outcome::error;
}

}  // namespace rheo::runtime::fmu
