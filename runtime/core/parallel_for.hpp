// Independent work items on several threads: harmonic grid points, fit data points.
//
// Contract: body(i) is called exactly once for every i in [0, count), from the calling thread
// and up to threads - 1 others; items are handed out one at a time (points differ widely in
// cost: a closed-form point takes microseconds, a resonant time-stepped one milliseconds).
// body must only write to item i's own output, so results do not depend on the thread count.
// The first exception thrown by any item is rethrown on the calling thread once every thread
// has stopped; items not yet started are then skipped.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace rheo::runtime {

// threads <= 0: every hardware thread; 1: the calling thread only (no thread is started).
inline int resolved_threads(int threads) {
  if (threads > 0) return threads;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

template <class Body>
void parallel_for(std::size_t count, int threads, Body&& body) {
  const auto workers = std::min<std::size_t>(static_cast<std::size_t>(resolved_threads(threads)), count);
  if (workers <= 1) {
    for (std::size_t i = 0; i < count; ++i) body(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr first_error;
  std::mutex error_mutex;
  auto work = [&]() noexcept {
    for (std::size_t i = next.fetch_add(1); i < count && !failed.load(); i = next.fetch_add(1)) {
      try {
        body(i);
      } catch (...) {
        const std::lock_guard lock(error_mutex);
        if (!first_error) first_error = std::current_exception();
        failed.store(true);
      }
    }
  };
  {
    std::vector<std::jthread> pool;
    pool.reserve(workers - 1);
    for (std::size_t t = 1; t < workers; ++t) pool.emplace_back(work);
    work();
  }
  if (first_error) std::rethrow_exception(first_error);
}

}  // namespace rheo::runtime
