// parallel_for: every item exactly once, the first failure carried to the caller, and results
// that do not depend on the thread count (a harmonic grid, bit for bit).
#include "runtime/core/parallel_for.hpp"

#include "runtime/protocols/harmonic.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <thread>
#include <vector>

namespace parallel_for_test {

using namespace rheo;

TEST_CASE("parallel_for calls the body once per item on any number of threads") {
  for (int threads : {0, 1, 2, 3, 16}) {
    std::vector<std::atomic<int>> calls(101);
    runtime::parallel_for(calls.size(), threads, [&](std::size_t i) { calls[i].fetch_add(1); });
    for (const auto& c : calls) CHECK(c.load() == 1);
  }
  int none = 0;
  runtime::parallel_for(0, 4, [&](std::size_t) { ++none; });
  CHECK(none == 0);
  CHECK(runtime::resolved_threads(0) >= 1);
  CHECK(runtime::resolved_threads(3) == 3);
}

TEST_CASE("parallel_for runs every item with the caller's evaluation context, and restores each thread's own") {
  runtime::PwlWarmStarts* const record = reinterpret_cast<runtime::PwlWarmStarts*>(std::uintptr_t{0x1000});
  const runtime::PwlWarmStarts* const start = reinterpret_cast<const runtime::PwlWarmStarts*>(std::uintptr_t{0x2000});
  for (int threads : {1, 2, 4}) {
    std::vector<std::atomic<int>> seen(200);
    {
      const runtime::EvaluationScope scope({record, start});
      runtime::parallel_for(seen.size(), threads, [&](std::size_t i) {
        const runtime::EvaluationContext& c = runtime::evaluation_context();
        seen[i].store(c.record == record && c.start == start ? 1 : -1);
      });
      CHECK(runtime::evaluation_context().record == record);
    }
    for (const auto& s : seen) CHECK(s.load() == 1);
    CHECK(runtime::evaluation_context().record == nullptr);
    CHECK(runtime::evaluation_context().start == nullptr);
    // Without a scope the items see none, whichever thread ran an item with one before.
    std::atomic<int> with_context{0};
    runtime::parallel_for(seen.size(), threads, [&](std::size_t) {
      if (runtime::evaluation_context().record != nullptr || runtime::evaluation_context().start != nullptr) with_context.fetch_add(1);
    });
    CHECK(with_context.load() == 0);
  }
}

TEST_CASE("parallel_for rethrows an item's exception on the caller after every thread stopped") {
  for (int threads : {1, 2, 4}) {
    // Items are handed out in order, so item 7 starts before any later one. Later items wait
    // for it to throw and then take 1 ms each: the other threads cannot race through the rest
    // in the moment between the throw and parallel_for noticing it.
    std::atomic<int> started{0};
    std::atomic<bool> thrown{false};
    CHECK_THROWS_WITH_AS(runtime::parallel_for(1000, threads,
                                               [&](std::size_t i) {
                                                 started.fetch_add(1);
                                                 if (i == 7) {
                                                   thrown.store(true);
                                                   throw std::domain_error("item 7 failed");
                                                 }
                                                 if (i < 7) return;
                                                 while (!thrown.load()) std::this_thread::yield();
                                                 std::this_thread::sleep_for(std::chrono::milliseconds(1));
                                               }),
                         "item 7 failed", std::domain_error);
    CHECK(started.load() >= 8);
    CHECK(started.load() < 1000);  // the remaining items are skipped
  }
}

TEST_CASE("a harmonic grid is the same bit for bit on one thread and on several") {
  const auto net = test::network_from("model n { spring e (k = 100) series { friction f (k = 50, fy = 2) maxwell m (k = 80, tau = 1 ms) } }", "n");
  runtime::HarmonicOptions one;
  one.steps_per_cycle = 256;
  runtime::HarmonicOptions several = one;
  several.threads = 3;
  const std::vector<double> amplitudes{0.01, 0.1, 1.0}, frequencies{1.0, 5.0, 20.0, 50.0};
  const auto a = runtime::simulate_harmonic_grid(net, amplitudes, frequencies, one);
  const auto b = runtime::simulate_harmonic_grid(net, amplitudes, frequencies, several);
  REQUIRE(a.size() == 12);
  REQUIRE(b.size() == 12);
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(b[i].amplitude == amplitudes[i / 4]);
    CHECK(b[i].frequency == frequencies[i % 4]);
    CHECK(b[i].measures.stiffness == a[i].measures.stiffness);
    CHECK(b[i].measures.phase == a[i].measures.phase);
    CHECK(b[i].cycles == a[i].cycles);
  }
}

}  // namespace parallel_for_test
