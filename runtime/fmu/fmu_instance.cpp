#include "runtime/fmu/fmu_instance.hpp"

namespace rheo::runtime::fmu {

void null_array(const char* what, std::size_t n) { throw UsageError(fmt::format("{} is NULL for {} values", what, n)); }

void no_variables_of(const char* type, std::size_t n) {
  if (n > 0) throw UsageError(fmt::format("the FMU has no {} variables ({} value references given)", type, n));
}

FmuInstance::~FmuInstance() {
  for (Snapshot* s : states_) delete s;
}

void* FmuInstance::new_state(Snapshot s) {
  auto owned = std::make_unique<Snapshot>(std::move(s));
  states_.insert(owned.get());
  return owned.release();
}

Snapshot& FmuInstance::state(void* handle) {
  const auto found = states_.find(static_cast<Snapshot*>(handle));
  if (found == states_.end()) throw UsageError("the FMU state passed is not one this instance gave out, or was freed");
  return **found;
}

void FmuInstance::free_state(void** address) {
  if (!address) return;
  auto* handle = static_cast<Snapshot*>(static_cast<void*>(address));
  const bool passed_itself = states_.count(handle) > 0;
  if (!passed_itself && !*address) return;
  if (!passed_itself) handle = &state(*address);
  states_.erase(handle);
  delete handle;
  if (!passed_itself) *address = nullptr;
}

}  // namespace rheo::runtime::fmu
