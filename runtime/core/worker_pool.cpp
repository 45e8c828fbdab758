#include "runtime/core/worker_pool.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

#include <algorithm>

namespace rheo::runtime {
namespace {

// Spins before sleeping: about 50-100 us on current x86 cores, longer than the gap between the
// evaluations of a fit, shorter than anything a user would notice as load.
constexpr int spin_rounds = 1 << 14;

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
    if (static_cast<std::uint64_t>(index) >= (seen & 0xffffU)) continue;
    call_(job_);
    if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) pending_.notify_one();
  }
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
  pending_.store(taking_part, std::memory_order_release);
  const std::uint64_t number = (ticket_.load(std::memory_order_relaxed) >> 16) + 1;
  ticket_.store((number << 16) | static_cast<std::uint64_t>(taking_part), std::memory_order_release);
  ticket_.notify_all();
  inside_job = true;
  call(job);
  inside_job = false;
  for (int left = pending_.load(std::memory_order_acquire); left != 0; left = pending_.load(std::memory_order_acquire)) wait_change(pending_, left);
}

}  // namespace rheo::runtime
