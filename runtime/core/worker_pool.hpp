// A process-wide pool of helper threads that live as long as the process, for parallel_for.
//
// Starting threads per call costs tens of microseconds, as much as evaluating a whole
// closed-form harmonic grid; a fit evaluates thousands of grids. The pool's helpers are started
// once (grown on demand), wait for a job by spinning briefly (a fit hands out the next job within
// microseconds) and then sleeping on an atomic wait, so an idle process uses no CPU.
//
// Contract of run(helpers, job): job() is called on the calling thread and on up to `helpers`
// helper threads at once; run returns after every call has returned. job must not throw (the
// callers wrap their work in a noexcept function that records failures). One job runs at a
// time: a call made while another is running (from another thread, or from inside a job) runs
// job() on the calling thread alone, so nesting never deadlocks.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace rheo::runtime {

class WorkerPool {
 public:
  static WorkerPool& instance();

  WorkerPool() = default;
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;
  ~WorkerPool();

  template <class Job>
  void run(int helpers, Job& job) noexcept {
    run_erased(helpers, &job, [](void* j) noexcept { (*static_cast<Job*>(j))(); });
  }

  int helper_count() const { return static_cast<int>(threads_.size()); }

 private:
  using Trampoline = void (*)(void*) noexcept;
  void run_erased(int helpers, void* job, Trampoline call) noexcept;
  void helper_loop(int index, std::uint64_t seen) noexcept;
  bool grow(int helpers) noexcept;

  std::mutex busy_;  // held by the caller of the running job
  std::vector<std::jthread> threads_;
  // (job number << 16) | number of helpers taking part: helpers [0, n) run the current job.
  // One word, so that a helper never pairs one job's number with another's count.
  std::atomic<std::uint64_t> ticket_{0};
  std::atomic<int> pending_{0};  // helpers of the current job still working
  std::atomic<bool> stopping_{false};
  void* job_ = nullptr;
  Trampoline call_ = nullptr;
};

}  // namespace rheo::runtime
