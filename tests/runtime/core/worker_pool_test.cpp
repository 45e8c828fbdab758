// WorkerPool: persistent helpers that run each job on the caller and the helpers asked for,
// grow on demand, and never deadlock when a job is nested or two callers race.
#include "runtime/core/worker_pool.hpp"

#include "runtime/core/parallel_for.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <numeric>
#include <thread>
#include <vector>

namespace worker_pool_test {

using namespace rheo;

// The caller's call waits (up to 10 s) until every helper asked for has joined, so that each
// has the time to take the job up: then every one does, and each once.
TEST_CASE("a job runs on the caller and on the helpers asked for that join while it runs, which stay for the next job") {
  runtime::WorkerPool pool;
  std::atomic<int> calls{0};
  int target = 0;  // the count of calls the caller waits for
  const std::thread::id caller = std::this_thread::get_id();
  auto job = [&]() noexcept {
    const int now = calls.fetch_add(1) + 1;
    if (std::this_thread::get_id() != caller) return;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    for (int seen = now; seen < target && std::chrono::steady_clock::now() < until; seen = calls.load()) std::this_thread::yield();
  };
  target = 4;
  pool.run(3, job);
  CHECK(calls.load() == 4);
  CHECK(pool.helper_count() == 3);
  int total = 4;
  // REQUIRE: after a round that went wrong the counts of the later rounds would be off too, and
  // each would wait its 10 s.
  for (int round = 0; round < 2000; ++round) {  // fewer helpers than there are, too: 1, 2, 3, 4 callers in turn
    total += round % 4 + 1;
    target = total;
    pool.run(round % 4, job);
    REQUIRE(calls.load() == total);  // no helper beyond those asked for, none twice, none after run returned
  }
  CHECK(pool.helper_count() == 3);
  target = total + 1;
  pool.run(0, job);
  CHECK(calls.load() == total + 1);
}

// A caller whose call returns at once does not wait for helpers to wake: each helper asked for
// takes part at most once, and a helper that joins after the caller's call has returned
// never does (its count would appear after run() returned).
TEST_CASE("a job the caller finishes alone is not waited on by helpers that wake late") {
  runtime::WorkerPool pool;
  std::atomic<int> calls{0};
  auto job = [&]() noexcept { calls.fetch_add(1); };
  for (int round = 0; round < 2000; ++round) {
    const int before = calls.load();
    pool.run(3, job);
    const int after = calls.load();
    CHECK(after - before >= 1);
    CHECK(after - before <= 4);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const int settled = calls.load();
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  CHECK(calls.load() == settled);  // nothing runs a job after its run() returned
}

TEST_CASE("every item of many short parallel_for calls is done once, on any number of threads") {
  for (int threads : {2, 3, 8}) {
    std::vector<int> done(997, 0);
    for (int round = 0; round < 300; ++round) runtime::parallel_for(done.size(), threads, [&](std::size_t i) { done[i] += 1; });
    CHECK(std::accumulate(done.begin(), done.end(), 0) == 300 * 997);
    CHECK(std::all_of(done.begin(), done.end(), [](int d) { return d == 300; }));
  }
}

TEST_CASE("a parallel_for inside an item, or beside another caller's, runs and finishes") {
  std::vector<std::atomic<int>> inner(64 * 50);
  runtime::parallel_for(64, 2, [&](std::size_t i) { runtime::parallel_for(50, 2, [&](std::size_t j) { inner[i * 50 + j].fetch_add(1); }); });
  CHECK(std::all_of(inner.begin(), inner.end(), [](const std::atomic<int>& c) { return c.load() == 1; }));

  std::vector<long> sums(2, 0);
  {
    std::vector<std::jthread> callers;
    for (std::size_t c = 0; c < 2; ++c)
      callers.emplace_back([&sums, c] {
        for (int round = 0; round < 200; ++round) {
          std::vector<long> items(100, 0);
          runtime::parallel_for(items.size(), 2, [&](std::size_t i) { items[i] = static_cast<long>(i); });
          sums[c] += std::accumulate(items.begin(), items.end(), 0L);
        }
      });
  }
  CHECK(sums[0] == 200L * 4950);
  CHECK(sums[1] == 200L * 4950);
}

}  // namespace worker_pool_test
