// A process-wide pool of helper threads that live as long as the process, for parallel_for.
//
// Starting threads per call costs tens of microseconds, as much as evaluating a whole
// closed-form harmonic grid; a fit evaluates thousands of grids. The pool's helpers are started
// once (grown on demand), wait for a job by spinning briefly (a fit hands out the next job within
// microseconds) and then sleeping on an atomic wait, so an idle process uses no CPU.
//
// Contract of run(helpers, job): job() is called on the calling thread and on those of up to
// `helpers` helper threads that take the job up while the caller's own call is still running;
// run returns after every call has returned. A helper that was not scheduled in time (more
// runnable threads than cores: two processes, or a machine busy with other work) does not join
// late and is not waited for, so the caller never idles for a helper that has no CPU: job()
// must therefore leave nothing undone when it returns on the caller (parallel_for's items are
// handed out from a shared counter, so the caller takes what no helper took). job must not
// throw (the callers wrap their work in a noexcept function that records failures). One job
// runs at a time: a call made while another is running (from another thread, or from inside a
// job) runs job() on the calling thread alone, so nesting never deadlocks.
//
// Measured: two diagnoses at once on this 2-core machine, each on 2 threads, when the caller
// waited for every helper to take part and helpers spun 16384 pauses: 274 s wall and 271 s CPU
// each, against 20.6 s wall and 40 s CPU for one alone (docs/performance.md, "Threads").
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
  bool join(std::uint64_t job) noexcept;  // a helper takes part in job number JOB, if it is still open
  void leave() noexcept;

  std::mutex busy_;  // held by the caller of the running job
  std::vector<std::jthread> threads_;
  // (job number << 16) | number of helpers taking part: helpers [0, n) run the current job.
  // One word, so that a helper never pairs one job's number with another's count.
  std::atomic<std::uint64_t> ticket_{0};
  // (job number << 32) | kClosed once the caller's own call has returned | helpers working on
  // it: a helper joins only an open job of the number it was woken for, and the caller waits
  // for the count to reach 0 after closing it.
  static constexpr std::uint64_t kClosed = std::uint64_t{1} << 31, kWorking = kClosed - 1;
  std::atomic<std::uint64_t> joined_{0};
  std::atomic<bool> stopping_{false};
  void* job_ = nullptr;
  Trampoline call_ = nullptr;
};

}  // namespace rheo::runtime
