#include "runtime/core/worker_pool.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

#include <algorithm>

namespace rheo::runtime {
namespace {

// Spins before sleeping: a few microseconds to tens of them (a pause costs 10-140 cycles by the
// core), about the gap between the evaluations of a fit. Longer spins cost the other runnable
// threads of a busy machine their CPU, and a caller no longer waits for a helper to wake.
constexpr int spin_rounds = 1 << 11;

inline void relax() noexcept {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#endif
}

// Waits until `value` differs from `old`: spinning first, then sleeping on the atomic.
template <class T>
T wait_change(const std::atomic<T>& value, T old) noexcept {
  for (int i = 0; i < spin_rounds; ++i) {
    const T now = value.load(std::memory_order_acquire);
    if (now != old) return now;
    relax();
  }
  for (;;) {
    value.wait(old, std::memory_order_acquire);
    const T now = value.load(std::memory_order_acquire);
    if (now != old) return now;
  }
}

thread_local bool inside_job = false;

}  // namespace

WorkerPool& WorkerPool::instance() {
  static WorkerPool pool;
  return pool;
}

WorkerPool::~WorkerPool() {
  stopping_.store(true, std::memory_order_release);
  ticket_.fetch_add(1 << 16, std::memory_order_acq_rel);
  ticket_.notify_all();
  threads_.clear();  // joins
}

bool WorkerPool::grow(int helpers) noexcept {
  try {
    while (static_cast<int>(threads_.size()) < helpers) {
      const int index = static_cast<int>(threads_.size());
      const std::uint64_t seen = ticket_.load(std::memory_order_acquire);  // before any job it must take part in
      threads_.emplace_back([this, index, seen] { helper_loop(index, seen); });
    }
  } catch (...) {  // no more threads (resource limits): run with the helpers there are
  }
  return !threads_.empty();
}

void WorkerPool::helper_loop(int index, std::uint64_t seen) noexcept {
  inside_job = true;  // a parallel_for inside a job runs on its own thread only
  for (;;) {
    seen = wait_change(ticket_, seen);
    if (stopping_.load(std::memory_order_acquire)) return;
    if (static_cast<std::uint64_t>(index) >= (seen & 0xffffU) || !join(seen >> 16)) continue;
    call_(job_);
    leave();
  }
}

bool WorkerPool::join(std::uint64_t job) noexcept {
  const std::uint64_t number = job & 0xffffffffU;
  std::uint64_t state = joined_.load(std::memory_order_acquire);
  for (;;) {
    if ((state >> 32) != number || (state & kClosed) != 0) return false;
    if (joined_.compare_exchange_weak(state, state + 1, std::memory_order_acq_rel, std::memory_order_acquire)) return true;
  }
}

void WorkerPool::leave() noexcept {
  const std::uint64_t after = joined_.fetch_sub(1, std::memory_order_acq_rel) - 1;
  if ((after & kWorking) == 0 && (after & kClosed) != 0) joined_.notify_one();
}

void WorkerPool::run_erased(int helpers, void* job, Trampoline call) noexcept {
  std::unique_lock lock(busy_, std::try_to_lock);
  if (inside_job || helpers <= 0 || !lock.owns_lock() || !grow(helpers)) {
    call(job);
    return;
  }
  const int taking_part = std::min({helpers, static_cast<int>(threads_.size()), 0xffff});
  job_ = job;
  call_ = call;
  const std::uint64_t number = (ticket_.load(std::memory_order_relaxed) >> 16) + 1;
  joined_.store((number & 0xffffffffU) << 32, std::memory_order_release);
  ticket_.store((number << 16) | static_cast<std::uint64_t>(taking_part), std::memory_order_release);
  ticket_.notify_all();
  inside_job = true;
  call(job);
  inside_job = false;
  // Closed: a helper not yet woken stays out; those working are waited for.
  for (std::uint64_t state = joined_.fetch_or(kClosed, std::memory_order_acq_rel) | kClosed; (state & kWorking) != 0;)
    state = wait_change(joined_, state);
}

}  // namespace rheo::runtime
