// The bookkeeping of one search (fit_search.hpp): counts evaluations, keeps the best point,
// reports progress, and stops on interrupt, when the budget is spent (some NLopt algorithms,
// e.g. DIRECT-L, overrun their own maxeval) or when the deadline would be passed.
//
// Batches: a batch of independent points (a differenced Jacobian's columns, the sampled
// starts) is evaluated up to `threads` at once and then recorded in the batch's order, so
// that counts, the best point, the progress calls and where the search stops are those of the
// same points evaluated one after another, whatever the thread count. Before a batch, as many
// of its leading points are admitted as the serial calls would have admitted (the deadline
// test assumes each costs the mean evaluation so far); after the admitted ones are recorded,
// the stop the next serial call would have thrown is thrown. Ctrl-C (the interrupt flag) is
// also seen inside a batch: its evaluations not yet begun are left out, and the search stops
// after the ones before the first of them.
// Concurrent evaluations call the objective or residuals from several threads: with threads
// > 1 they must be safe for that (each evaluation with its own model state). Inside a batch an
// evaluation's own parallel_for (its harmonic points) runs on its thread alone.
#pragma once

#include "runtime/fit/fit_search.hpp"

#include <atomic>
#include <chrono>
#include <cstddef>
#include <exception>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rheo::runtime {

// What the tracker throws to end a search (fit_search.cpp catches them).
struct Interrupted {};
struct Exhausted {};
struct OutOfTime {};

class Tracker {
 public:
  // With RESIDUALS the objective is their sum of squares and the last residuals are kept.
  Tracker(const Objective& objective, const Residuals* residuals, const std::function<void(const SearchProgress&)>& progress,
          const std::atomic<bool>* interrupt, const SearchSettings& settings);

  // The objective at z. The first call (the start) is always evaluated, so that the best point
  // has a value.
  double operator()(const std::vector<double>& z);
  // The residuals at z (empty where they could not be evaluated), counted like the objective.
  const std::vector<double>& residuals(const std::vector<double>& z);
  // The objective, and the residuals, at each of ZS (batches, above).
  std::vector<double> values(const std::vector<std::vector<double>>& zs);
  std::vector<std::vector<double>> residuals(const std::vector<std::vector<double>>& zs);

  bool has_residuals() const { return residuals_ != nullptr; }
  bool has_jacobian() const { return static_cast<bool>(jacobian_); }
  bool has_reduced_jacobian() const { return static_cast<bool>(reduced_jacobian_); }
  // The settings' reduced Jacobian at z with STEPS (SearchSettings::reduced_jacobian): its moved
  // points are admitted as a batch's would be (all of them, or the stop the first one left out
  // would meet is thrown), then each is recorded as an evaluation with its value; nullopt
  // (nothing recorded) where it cannot be formed.
  std::optional<ReducedJacobian> reduced_jacobian(const std::vector<double>& z, const std::vector<double>& steps);
  // The settings' Jacobian at z, counted as one evaluation (the stops as for an evaluation); a
  // matrix with no columns where it throws NumericalError or is not finite.
  Eigen::MatrixXd jacobian(const std::vector<double>& z);
  // With a deadline: caps the budget at the evaluations the time left affords at the mean cost
  // so far, less the reserve, so that the stages share what can actually run (or restores it
  // when the time left affords it all). True when that cap is below the budget given.
  bool cap_to_deadline();
  int limit() const { return limit_; }
  bool capped() const { return limit_ < budget_; }
  void stage(const char* name) { stage_ = name; }
  int evaluations() const { return evaluations_; }
  int non_finite() const { return non_finite_; }
  const std::string& first_failure() const { return first_failure_; }
  double best_value() const { return best_value_; }
  const std::vector<double>& best_z() const { return best_z_; }

 private:
  // One evaluation's result, made without touching the tracker (safe on any thread).
  struct Outcome {
    double value = 0.0;             // NaN where not simulable
    std::vector<double> residuals;  // with residuals_: empty where not simulable
    std::string failure;            // a NumericalError's message
    std::exception_ptr error;       // any other exception: passes through when recorded
    bool skipped = false;           // not begun: interrupted before it
  };
  Outcome evaluate(const std::vector<double>& z) const;
  // The stop the serial call for the AHEAD-th next evaluation would throw, or null.
  std::exception_ptr stop_before(int ahead, std::chrono::steady_clock::time_point now) const;
  // Admits, evaluates and records ZS (batches, above); the outcomes in order.
  std::vector<Outcome> batch(const std::vector<std::vector<double>>& zs);
  void record(const std::vector<double>& z, const Outcome& outcome);
  void report_progress() const;

  const Objective& objective_;
  const Residuals* residuals_;
  ResidualJacobian jacobian_;
  ReducedResidualJacobian reduced_jacobian_;
  std::vector<double> last_residuals_;
  const std::function<void(const SearchProgress&)>& progress_;
  const std::atomic<bool>* interrupt_;
  int threads_;
  int budget_;  // max_evaluations
  int limit_;   // the budget, or less where the deadline affords less
  std::optional<std::chrono::steady_clock::time_point> deadline_;
  int reserve_;
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
  int evaluations_ = 0;
  int non_finite_ = 0;
  double best_value_;
  std::vector<double> best_z_;
  std::string first_failure_;
  const char* stage_ = "";
};

}  // namespace rheo::runtime
