// Independent work items on several threads: harmonic grid points, fit data points.
//
// Contract: body(i) is called exactly once for every i in [0, count), from the calling thread
// and up to threads - 1 others. Items are handed out in shrinking runs of consecutive items
// (remaining / (4 threads), at least 1), so that cheap items (a closed-form point takes a
// microsecond) do not pay a hand-out each while dear ones (a resonant time-stepped point takes
// milliseconds) still balance at the end.
// body must only write to item i's own output, so results do not depend on the thread count.
// The first exception thrown by any item is rethrown on the calling thread once every thread
// has stopped; items not yet started are then skipped.
// The other threads are the process's persistent helpers (worker_pool.hpp): nothing is
// started per call. A parallel_for inside an item, or one called while another runs, runs on
// its calling thread alone.
// Every item runs with the calling thread's evaluation context (evaluation_context.hpp).
#pragma once

#include "runtime/core/evaluation_context.hpp"
#include "runtime/core/worker_pool.hpp"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>

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
  const EvaluationContext context = evaluation_context();
  auto work = [&]() noexcept {
    const EvaluationScope scope(context);
    for (;;) {
      const std::size_t seen = next.load(std::memory_order_relaxed);
      const std::size_t chunk = std::max<std::size_t>(1, (count - std::min(seen, count)) / (4 * workers));
      const std::size_t begin = next.fetch_add(chunk);
      if (begin >= count) return;
      const std::size_t end = std::min(count, begin + chunk);
      for (std::size_t i = begin; i < end && !failed.load(std::memory_order_relaxed); ++i) {
        try {
          body(i);
        } catch (...) {
          const std::lock_guard lock(error_mutex);
          if (!first_error) first_error = std::current_exception();
          failed.store(true);
        }
      }
      if (failed.load()) return;
    }
  };
  WorkerPool::instance().run(static_cast<int>(workers) - 1, work);
  if (first_error) std::rethrow_exception(first_error);
}

}  // namespace rheo::runtime
