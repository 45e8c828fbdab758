// What one evaluation (a fit's residuals at one parameter vector) shares with the threads its
// items run on: set for the calling thread by an EvaluationScope, carried by parallel_for to the
// threads that run its items (parallel_for.hpp), so that a harmonic point sees the context of
// the evaluation it belongs to whichever thread computes it.
//
// Today it holds the warm starts of the event path (closed_form/pwl_warm_start.hpp): where the
// evaluation records the periodic states of its piecewise-linear subtrees, and where their
// shooting starts from instead of the cold (all stuck) start. Both null: cold, nothing recorded.
#pragma once

namespace rheo::runtime {

class PwlWarmStarts;

struct EvaluationContext {
  PwlWarmStarts* record = nullptr;       // the periodic states solved are recorded here
  const PwlWarmStarts* start = nullptr;  // the shooting starts from these where they hold the point
};

// The context of the evaluation running on this thread.
inline EvaluationContext& evaluation_context() {
  thread_local EvaluationContext context;
  return context;
}

// Sets this thread's context for its lifetime, then restores the one before.
class EvaluationScope {
 public:
  explicit EvaluationScope(const EvaluationContext& context) noexcept : saved_(evaluation_context()) { evaluation_context() = context; }
  ~EvaluationScope() { evaluation_context() = saved_; }
  EvaluationScope(const EvaluationScope&) = delete;
  EvaluationScope& operator=(const EvaluationScope&) = delete;

 private:
  EvaluationContext saved_;
};

}  // namespace rheo::runtime
