// The instance both FMI versions' entry points share: the guard's statuses and messages for each
// kind of exception, and the registry of FMU states (stale and foreign handles refused, both ways
// of passing a handle to free it).
#include "runtime/fmu/fmu_instance.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace fmu_instance_test {

using namespace rheo;
using runtime::fmu::Outcome;

namespace {

struct RecordingInstance final : runtime::fmu::FmuInstance {
  using FmuInstance::FmuInstance;
  mutable std::vector<std::string> log;
  void log_error(const std::string& message) const override { log.push_back(message); }
};

}  // namespace

TEST_CASE("fmu instance: the guard returns ok, or logs what was thrown as an error, and memory exhaustion as fatal") {
  RecordingInstance i("one");
  CHECK(i.name() == "one");
  int calls = 0;
  CHECK(runtime::fmu::guarded(i, "fmiXDo", [&](RecordingInstance&) { ++calls; }) == Outcome::ok);
  CHECK(calls == 1);
  CHECK(i.log.empty());
  CHECK(runtime::fmu::guarded(i, "fmiXDo", [](RecordingInstance&) { throw DataError("u = nan: it must be a finite number"); }) == Outcome::error);
  CHECK(i.log.back() == "fmiXDo: u = nan: it must be a finite number");
  CHECK(runtime::fmu::guarded(i, "fmiXDo", [](RecordingInstance&) { throw std::bad_alloc(); }) == Outcome::fatal);
  CHECK(i.log.back() == "fmiXDo: out of memory");
  CHECK(runtime::fmu::guarded(i, "fmiXDo", [](RecordingInstance&) { throw std::logic_error("broken"); }) == Outcome::error);
  CHECK(i.log.back() == "fmiXDo: internal error: broken; please report it to rheo with the FMU");
  CHECK(i.log.size() == 3);
}

TEST_CASE("fmu instance: states are handed out, found, refused when foreign or freed, and freed by address or by handle") {
  RecordingInstance i("states");
  runtime::fmu::Snapshot s;
  s.time = 1.5;
  void* a = i.new_state(s);
  void* b = i.new_state(s);
  CHECK(a != b);
  CHECK(i.state(a).time == 1.5);
  double foreign = 0.0;
  CHECK_THROWS_AS(i.state(&foreign), UsageError);
  i.free_state(&a);  // the standard's way: the handle's address, which the call sets to null
  CHECK(a == nullptr);
  void* freed = b;
  i.free_state(static_cast<void**>(b));  // the handle itself (fmusim 31d7d40): freed all the same
  CHECK_THROWS_WITH_AS(i.state(freed), doctest::Contains("not one this instance gave out, or was freed"), UsageError);
  void* none = nullptr;
  i.free_state(&none);  // nothing to free
  i.free_state(nullptr);
  CHECK_THROWS_AS(runtime::fmu::no_variables_of("Int32", 1), UsageError);
  CHECK_NOTHROW(runtime::fmu::no_variables_of("Int32", 0));
  const double* null_values = nullptr;
  CHECK_THROWS_WITH_AS(runtime::fmu::require_array(null_values, 2, "values"), doctest::Contains("values is NULL for 2 values"), UsageError);
  CHECK_NOTHROW(runtime::fmu::require_array(null_values, 0, "values"));
  // States left when the instance goes are freed with it (the sanitizer builds find a leak).
  i.new_state(s);
}

}  // namespace fmu_instance_test
