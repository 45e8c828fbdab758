// The evaluation context: a scope sets this thread's and restores the one before, nested or not;
// other threads keep their own (parallel_for_test: carried to a parallel_for's items).
#include "runtime/core/evaluation_context.hpp"

#include <doctest/doctest.h>

#include <cstdint>
#include <thread>

namespace evaluation_context_test {

using namespace rheo;

TEST_CASE("an evaluation scope sets this thread's context and restores the one before, nested or not") {
  auto* const a = reinterpret_cast<runtime::PwlWarmStarts*>(std::uintptr_t{0x1000});
  auto* const b = reinterpret_cast<const runtime::PwlWarmStarts*>(std::uintptr_t{0x2000});
  CHECK(runtime::evaluation_context().record == nullptr);
  CHECK(runtime::evaluation_context().start == nullptr);
  {
    const runtime::EvaluationScope outer({a, nullptr});
    CHECK(runtime::evaluation_context().record == a);
    {
      const runtime::EvaluationScope inner({nullptr, b});
      CHECK(runtime::evaluation_context().record == nullptr);
      CHECK(runtime::evaluation_context().start == b);
      const runtime::PwlWarmStarts* seen = b;
      std::thread([&] { seen = runtime::evaluation_context().start; }).join();
      CHECK(seen == nullptr);  // another thread's own
    }
    CHECK(runtime::evaluation_context().record == a);
    CHECK(runtime::evaluation_context().start == nullptr);
  }
  CHECK(runtime::evaluation_context().record == nullptr);
}

}  // namespace evaluation_context_test
