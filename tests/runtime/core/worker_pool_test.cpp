// WorkerPool: persistent helpers that run each job on the caller and the helpers asked for,
// grow on demand, and never deadlock when a job is nested or two callers race.
#include "runtime/core/worker_pool.hpp"

#include "runtime/core/parallel_for.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <numeric>
#include <thread>
#include <vector>

using namespace rheo;

TEST_CASE("a job runs on the caller and on the helpers asked for, which stay for the next job") {
  runtime::WorkerPool pool;
  std::atomic<int> calls{0};
  auto job = [&]() noexcept { calls.fetch_add(1); };
  pool.run(3, job);
  CHECK(calls.load() == 4);
  CHECK(pool.helper_count() == 3);
  for (int round = 0; round < 2000; ++round) pool.run(round % 4, job);  // fewer helpers than there are, too
  CHECK(calls.load() == 4 + 5000);                                      // rounds take 1, 2, 3, 4 callers in turn: 10 calls per 4 rounds
  CHECK(pool.helper_count() == 3);
  pool.run(0, job);
  CHECK(calls.load() == 4 + 5000 + 1);
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
