#include "runtime/fit/search_tracker.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/core/parallel_for.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace rheo::runtime {

Tracker::Tracker(const Objective& objective, const Residuals* residuals, const std::function<void(const SearchProgress&)>& progress,
                 const std::atomic<bool>* interrupt, const SearchSettings& settings)
    : objective_(objective),
      residuals_(residuals),
      jacobian_(residuals ? settings.jacobian : ResidualJacobian{}),
      reduced_jacobian_(settings.reduced_jacobian),
      progress_(progress),
      interrupt_(interrupt),
      threads_(settings.threads),
      budget_(std::max(1, settings.max_evaluations)),
      limit_(budget_),
      deadline_(settings.deadline),
      reserve_(std::max(0, settings.reserve_evaluations)),
      best_value_(std::numeric_limits<double>::infinity()) {}

Tracker::Outcome Tracker::evaluate(const std::vector<double>& z) const {
  Outcome o;
  o.value = std::numeric_limits<double>::quiet_NaN();
  try {
    if (residuals_ != nullptr) {
      o.residuals = (*residuals_)(z);
      o.value = std::accumulate(o.residuals.begin(), o.residuals.end(), 0.0, [](double sum, double r) { return sum + r * r; });
    } else {
      o.value = objective_(z);
    }
  } catch (const NumericalError& e) {  // this point cannot be simulated: rejected like NaN
    o.failure = e.what();
  } catch (...) {
    o.error = std::current_exception();
  }
  return o;
}

std::exception_ptr Tracker::stop_before(int ahead, std::chrono::steady_clock::time_point now) const {
  const int count = evaluations_ + ahead;
  if (count > 0 && interrupt_ && interrupt_->load(std::memory_order_relaxed)) return std::make_exception_ptr(Interrupted{});
  if (count >= limit_) return std::make_exception_ptr(Exhausted{});
  if (evaluations_ > 0 && deadline_ && now + (now - started_) / evaluations_ * (1 + ahead + reserve_) > *deadline_)
    return std::make_exception_ptr(OutOfTime{});
  return nullptr;
}

void Tracker::record(const std::vector<double>& z, const Outcome& outcome) {
  if (!outcome.failure.empty() && first_failure_.empty()) first_failure_ = outcome.failure;
  ++evaluations_;
  if (!std::isfinite(outcome.value)) ++non_finite_;
  if (std::isfinite(outcome.value) && outcome.value < best_value_) {
    best_value_ = outcome.value;
    best_z_ = z;
  }
  report_progress();
}

void Tracker::report_progress() const {
  if (progress_)
    progress_({evaluations_, best_value_, stage_, limit_, std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count()});
}

double Tracker::operator()(const std::vector<double>& z) {
  if (const std::exception_ptr stop = stop_before(0, std::chrono::steady_clock::now())) std::rethrow_exception(stop);
  Outcome outcome = evaluate(z);
  if (outcome.error) std::rethrow_exception(outcome.error);
  record(z, outcome);
  last_residuals_ = std::move(outcome.residuals);
  return outcome.value;
}

const std::vector<double>& Tracker::residuals(const std::vector<double>& z) {
  (*this)(z);
  return last_residuals_;
}

Eigen::MatrixXd Tracker::jacobian(const std::vector<double>& z) {
  if (const std::exception_ptr stop = stop_before(0, std::chrono::steady_clock::now())) std::rethrow_exception(stop);
  Eigen::MatrixXd j;
  try {
    j = jacobian_(z);
  } catch (const NumericalError&) {  // differenced instead
    j.resize(0, 0);
  }
  ++evaluations_;
  report_progress();
  return j.allFinite() ? j : Eigen::MatrixXd();
}

std::optional<ReducedJacobian> Tracker::reduced_jacobian(const std::vector<double>& z, const std::vector<double>& steps) {
  const int moved = static_cast<int>(std::count_if(steps.begin(), steps.end(), [](double h) { return h != 0.0; }));
  const auto now = std::chrono::steady_clock::now();
  for (int ahead = 0; ahead < moved; ++ahead)
    if (const std::exception_ptr stop = stop_before(ahead, now)) std::rethrow_exception(stop);
  std::optional<ReducedJacobian> reduced = reduced_jacobian_(z, steps);
  if (!reduced) return std::nullopt;
  std::vector<double> at = z;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    if (steps[k] == 0.0) continue;
    at[k] = z[k] + steps[k];
    Outcome outcome;
    outcome.value = k < reduced->moved_values.size() ? reduced->moved_values[k] : std::numeric_limits<double>::quiet_NaN();
    record(at, outcome);
    at[k] = z[k];
  }
  return reduced;
}

std::vector<Tracker::Outcome> Tracker::batch(const std::vector<std::vector<double>>& zs) {
  const auto now = std::chrono::steady_clock::now();
  std::size_t admitted = 0;
  std::exception_ptr stop;
  while (admitted < zs.size() && !(stop = stop_before(static_cast<int>(admitted), now))) ++admitted;
  std::vector<Outcome> outcomes(admitted);
  // Whole rounds of `threads` evaluations side by side, one on each thread (their points
  // serially: parallel_for inside a job runs on its thread alone), then the rest one after
  // another, each spreading its points over every thread. So a batch of n on T threads keeps
  // every thread busy whether its points are cheap (a closed-form point: the hand-out between
  // points would cost as much as the point) or dear (a time-stepped point).
  const auto threads = static_cast<std::size_t>(resolved_threads(threads_));
  const std::size_t side_by_side = threads > 1 ? admitted / threads * threads : 0;
  // Ctrl-C during the batch: the evaluations not yet begun are left out.
  auto evaluate_unless_interrupted = [&](std::size_t i) {
    if (evaluations_ + static_cast<int>(i) > 0 && interrupt_ && interrupt_->load(std::memory_order_relaxed)) outcomes[i].skipped = true;
    else outcomes[i] = evaluate(zs[i]);
  };
  parallel_for(side_by_side, threads_, evaluate_unless_interrupted);
  for (std::size_t i = side_by_side; i < admitted; ++i) evaluate_unless_interrupted(i);
  for (std::size_t i = 0; i < admitted; ++i) {
    if (outcomes[i].skipped) throw Interrupted{};
    if (outcomes[i].error) std::rethrow_exception(outcomes[i].error);
    record(zs[i], outcomes[i]);
  }
  if (stop) std::rethrow_exception(stop);
  return outcomes;
}

std::vector<double> Tracker::values(const std::vector<std::vector<double>>& zs) {
  std::vector<double> out;
  for (const Outcome& o : batch(zs)) out.push_back(o.value);
  return out;
}

std::vector<std::vector<double>> Tracker::residuals(const std::vector<std::vector<double>>& zs) {
  std::vector<std::vector<double>> out;
  for (Outcome& o : batch(zs)) out.push_back(std::move(o.residuals));
  return out;
}

bool Tracker::cap_to_deadline() {
  if (!deadline_ || evaluations_ == 0) return false;
  const auto now = std::chrono::steady_clock::now();
  const double mean = std::chrono::duration<double>(now - started_).count() / evaluations_;
  const double left = std::chrono::duration<double>(*deadline_ - now).count();
  const double affordable = mean > 0.0 ? std::floor(left / mean) - reserve_ : budget_;
  limit_ = affordable < budget_ - evaluations_ ? evaluations_ + static_cast<int>(std::max(0.0, affordable)) : budget_;
  return limit_ < budget_;
}

}  // namespace rheo::runtime
