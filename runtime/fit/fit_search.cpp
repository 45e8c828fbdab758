#include "runtime/fit/fit_search.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/fit/levenberg_marquardt.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

namespace rheo::runtime {
namespace {

struct Interrupted {};
struct Exhausted {};
struct OutOfTime {};
struct LocalBudgetSpent {};

// A Levenberg-Marquardt local search that has not converged after this many Jacobians is
// crawling along a curved valley; its budget serves the next start better.
constexpr int kMaxLocalIterations = 50;

// Counts evaluations, keeps the best point, reports progress, and stops on interrupt, when the
// budget is spent (some NLopt algorithms, e.g. DIRECT-L, overrun their own maxeval) or when the
// deadline would be passed (fit_search.hpp).
class Tracker {
 public:
  // With RESIDUALS the objective is their sum of squares and the last residuals are kept.
  Tracker(const Objective& objective, const Residuals* residuals, const std::function<void(const SearchProgress&)>& progress,
          const std::atomic<bool>* interrupt, const SearchSettings& settings)
      : objective_(objective),
        residuals_(residuals),
        progress_(progress),
        interrupt_(interrupt),
        budget_(std::max(1, settings.max_evaluations)),
        limit_(budget_),
        deadline_(settings.deadline),
        reserve_(std::max(0, settings.reserve_evaluations)) {}

  // The first call (the start) is always evaluated, so that the best point has a value.
  double operator()(const std::vector<double>& z) {
    if (evaluations_ > 0 && interrupt_ && interrupt_->load(std::memory_order_relaxed)) throw Interrupted{};
    if (evaluations_ >= limit_) throw Exhausted{};
    if (evaluations_ > 0 && deadline_) {
      const auto now = std::chrono::steady_clock::now();
      if (now + (now - started_) / evaluations_ * (1 + reserve_) > *deadline_) throw OutOfTime{};
    }
    double value = std::numeric_limits<double>::quiet_NaN();
    last_residuals_.clear();
    try {
      if (residuals_ != nullptr) {
        last_residuals_ = (*residuals_)(z);
        value = std::accumulate(last_residuals_.begin(), last_residuals_.end(), 0.0, [](double sum, double r) { return sum + r * r; });
      } else {
        value = objective_(z);
      }
    } catch (const NumericalError& e) {  // this point cannot be simulated: rejected like NaN
      if (first_failure_.empty()) first_failure_ = e.what();
    }
    ++evaluations_;
    if (!std::isfinite(value)) ++non_finite_;
    if (std::isfinite(value) && value < best_value_) {
      best_value_ = value;
      best_z_ = z;
    }
    if (progress_) progress_({evaluations_, best_value_, stage_});
    return value;
  }
  // The residuals at z (empty where they could not be evaluated), counted like the objective.
  const std::vector<double>& residuals(const std::vector<double>& z) {
    (*this)(z);
    return last_residuals_;
  }
  bool has_residuals() const { return residuals_ != nullptr; }
  // With a deadline: caps the budget at the evaluations the time left affords at the mean cost
  // so far, less the reserve, so that the stages share what can actually run (or restores it
  // when the time left affords it all). True when that cap is below the budget given.
  bool cap_to_deadline() {
    if (!deadline_ || evaluations_ == 0) return false;
    const auto now = std::chrono::steady_clock::now();
    const double mean = std::chrono::duration<double>(now - started_).count() / evaluations_;
    const double left = std::chrono::duration<double>(*deadline_ - now).count();
    const double affordable = mean > 0.0 ? std::floor(left / mean) - reserve_ : budget_;
    limit_ = affordable < budget_ - evaluations_ ? evaluations_ + static_cast<int>(std::max(0.0, affordable)) : budget_;
    return limit_ < budget_;
  }
  int limit() const { return limit_; }
  bool capped() const { return limit_ < budget_; }
  void stage(const char* name) { stage_ = name; }
  int evaluations() const { return evaluations_; }
  int non_finite() const { return non_finite_; }
  const std::string& first_failure() const { return first_failure_; }
  double best_value() const { return best_value_; }
  const std::vector<double>& best_z() const { return best_z_; }

 private:
  const Objective& objective_;
  const Residuals* residuals_;
  std::vector<double> last_residuals_;
  const std::function<void(const SearchProgress&)>& progress_;
  const std::atomic<bool>* interrupt_;
  int budget_;  // max_evaluations
  int limit_;   // the budget, or less where the deadline affords less
  std::optional<std::chrono::steady_clock::time_point> deadline_;
  int reserve_;
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
  int evaluations_ = 0;
  int non_finite_ = 0;
  double best_value_ = std::numeric_limits<double>::infinity();
  std::vector<double> best_z_;
  std::string first_failure_;
  const char* stage_ = "";
};

bool is_global(Algorithm a) { return a == Algorithm::direct_l || a == Algorithm::crs2 || a == Algorithm::isres || a == Algorithm::mlsl; }

// Radical inverse of `index` in base `base`: the Halton coordinate.
double radical_inverse(unsigned long index, unsigned base) {
  double result = 0.0, fraction = 1.0 / base;
  for (; index > 0; index /= base, fraction /= base) result += fraction * static_cast<double>(index % base);
  return result;
}

std::vector<unsigned> first_primes(std::size_t count) {
  std::vector<unsigned> primes;
  for (unsigned candidate = 2; primes.size() < count; ++candidate)
    if (std::none_of(primes.begin(), primes.end(), [&](unsigned p) { return candidate % p == 0; })) primes.push_back(candidate);
  return primes;
}

// SAMPLES points of the box a decade (log coordinates) or a quarter of the range (linear ones)
// either side of START, within the bounds, on a Halton sequence shifted by SEED (Cranley-
// Patterson rotation), each with its objective value: best first, non-finite values last.
std::vector<std::pair<double, std::vector<double>>> sample_box(const Objective& objective, const std::vector<double>& start,
                                                               const std::vector<double>& lower, const std::vector<double>& upper,
                                                               const std::vector<bool>& logarithmic, int samples, unsigned long seed) {
  const std::size_t n = start.size();
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::vector<unsigned> primes = first_primes(n);
  std::vector<double> shift(n), box_lo(n), box_hi(n);
  for (std::size_t j = 0; j < n; ++j) {
    shift[j] = unit(random);
    const double half = logarithmic[j] ? std::log(10.0) : 0.25 * (upper[j] - lower[j]);
    box_lo[j] = std::max(lower[j], start[j] - half);
    box_hi[j] = std::min(upper[j], start[j] + half);
  }
  std::vector<std::pair<double, std::vector<double>>> sampled;
  std::vector<double> z(n);
  for (int s = 1; s <= samples; ++s) {
    for (std::size_t j = 0; j < n; ++j) {
      const double t = std::fmod(radical_inverse(static_cast<unsigned long>(s), primes[j]) + shift[j], 1.0);
      z[j] = box_lo[j] + t * (box_hi[j] - box_lo[j]);
    }
    sampled.emplace_back(objective(z), z);
  }
  // Non-finite samples sort last (NaN would break the ordering std::sort relies on).
  auto key = [](double v) { return std::isfinite(v) ? v : std::numeric_limits<double>::infinity(); };
  std::stable_sort(sampled.begin(), sampled.end(), [&](const auto& a, const auto& b) { return key(a.first) < key(b.first); });
  return sampled;
}

// Levenberg-Marquardt from FROM on the tracker's residuals, within BUDGET evaluations; the
// NLopt-style status. A start whose residuals are not finite ends it at once.
std::string least_squares_local(Tracker& tracker, const std::vector<double>& from, int budget, const std::vector<double>& lower,
                                const std::vector<double>& upper, double tolerance) {
  const int first = tracker.evaluations();
  LeastSquaresProblem problem;
  problem.residuals = [&](const Eigen::VectorXd& x) {
    if (tracker.evaluations() - first >= budget) throw LocalBudgetSpent{};
    const std::vector<double>& r = tracker.residuals(std::vector<double>(x.data(), x.data() + x.size()));
    return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size())));
  };
  LevenbergMarquardtSettings lm;
  lm.max_iterations = std::min(budget, kMaxLocalIterations);
  lm.step_tolerance = tolerance;
  lm.decrease_tolerance = 1e-9;  // as the NLopt local stages' relative f tolerance
  // Steps of 1e-6 max(|z|, 1): for z = ln p a relative change of 1e-6 to ~1e-5 in the parameter,
  // above the event-driven and time-stepped paths' convergence noise, below the response's curvature.
  lm.difference_step = 1e-6;
  auto to_eigen = [](const std::vector<double>& v) { return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size())); };
  try {
    return levenberg_marquardt(problem, to_eigen(from), to_eigen(lower), to_eigen(upper), lm).status;
  } catch (const LocalBudgetSpent&) {
    return "MAXEVAL_REACHED";
  } catch (const NumericalError&) {
    return "NO_FINITE_START";
  }
}

SearchResult search_with(const Objective& objective, const Residuals* residuals, const std::vector<double>& start, const std::vector<double>& lower,
                         const std::vector<double>& upper, const std::vector<bool>& logarithmic, const SearchSettings& settings,
                         const std::function<void(const SearchProgress&)>& progress, const std::atomic<bool>* interrupt) {
  const std::size_t n = start.size();
  Tracker tracker(objective, residuals, progress, interrupt, settings);
  const Objective tracked = [&](const std::vector<double>& z) { return tracker(z); };
  SearchResult result;
  auto remaining = [&] { return tracker.limit() - tracker.evaluations(); };
  auto local = [&](const std::vector<double>& from, int budget, Algorithm algorithm) {
    if (tracker.has_residuals() && !settings.algorithm) {
      result.status = least_squares_local(tracker, from, std::max(1, budget), lower, upper, settings.tolerance);
      return;
    }
    OptimizerSettings o;
    o.algorithm = algorithm;
    o.max_evaluations = std::max(1, budget);
    o.relative_x_tolerance = settings.tolerance;
    o.relative_f_tolerance = 1e-9;
    o.seed = settings.seed;
    result.status = minimize(tracked, from, lower, upper, o).status;
  };
  const Algorithm local_algorithm = settings.algorithm && !is_global(*settings.algorithm) ? *settings.algorithm : Algorithm::bobyqa;
  result.status = "MAXEVAL_REACHED";  // when the budget leaves no local stage to run
  try {
    tracker.stage("start");
    tracked(start);
    tracker.cap_to_deadline();
    if (settings.algorithm && is_global(*settings.algorithm)) {
      if (remaining() > 0) {
        tracker.stage("global");
        OptimizerSettings o;
        o.algorithm = *settings.algorithm;
        o.max_evaluations = std::max(1, remaining() / 2);
        o.seed = settings.seed;
        minimize(tracked, start, lower, upper, o);
      }
    } else {
      // Sample a box around the start, then run local searches from the start and the best samples.
      tracker.stage("sample");
      const int wanted_samples = settings.samples >= 0 ? settings.samples : std::max(10 * static_cast<int>(n), 40);
      const auto sampled = sample_box(tracked, start, lower, upper, logarithmic, std::max(0, std::min(wanted_samples, remaining() / 4)),
                                      settings.seed);
      // Each distinct point once (an extra start may be the start itself).
      std::vector<std::vector<double>> starts{start};
      auto add = [&](const std::vector<double>& point) {
        if (std::find(starts.begin(), starts.end(), point) == starts.end()) starts.push_back(point);
      };
      for (const auto& extra : settings.extra_starts) add(extra);
      const std::size_t wanted = static_cast<std::size_t>(std::max(settings.starts, 1));
      for (const auto& [value, point] : sampled) {
        if (starts.size() >= wanted) break;
        if (std::isfinite(value)) add(point);
      }
      tracker.stage("local");
      for (std::size_t k = 0; k < starts.size(); ++k) {
        tracker.cap_to_deadline();
        if (remaining() <= 0) break;
        local(starts[k], remaining() / static_cast<int>(starts.size() - k + 1), local_algorithm);
      }
    }
    tracker.stage("polish");
    tracker.cap_to_deadline();
    if (remaining() > 0 && !tracker.best_z().empty()) local(tracker.best_z(), remaining(), local_algorithm);
  } catch (const Exhausted&) {
    result.status = tracker.capped() ? "TIME_LIMIT_REACHED" : "MAXEVAL_REACHED";
    result.out_of_time = tracker.capped();
  } catch (const OutOfTime&) {
    result.status = "TIME_LIMIT_REACHED";
    result.out_of_time = true;
  } catch (const Interrupted&) {
    result.interrupted = true;
    result.status = "interrupted";
  }
  // A stage that ran out of a budget the time limit had cut.
  if (tracker.capped() && result.status == "MAXEVAL_REACHED") result.status = "TIME_LIMIT_REACHED", result.out_of_time = true;
  if (tracker.best_z().empty() && !result.interrupted)
    throw NumericalError(
        fmt::format("none of the {} trial points of the search gave a finite objective{}; check that the data and the "
                    "parameters' bounds describe something this model can simulate",
                    tracker.evaluations(), tracker.first_failure().empty() ? "" : fmt::format(" (first failure: {})", tracker.first_failure())));
  result.z = tracker.best_z().empty() ? start : tracker.best_z();
  result.value = tracker.best_value();
  result.evaluations = tracker.evaluations();
  result.non_finite = tracker.non_finite();
  result.first_failure = tracker.first_failure();
  return result;
}

}  // namespace

SearchResult search(const Objective& objective, const std::vector<double>& start, const std::vector<double>& lower,
                    const std::vector<double>& upper, const std::vector<bool>& logarithmic, const SearchSettings& settings,
                    const std::function<void(const SearchProgress&)>& progress, const std::atomic<bool>* interrupt) {
  return search_with(objective, nullptr, start, lower, upper, logarithmic, settings, progress, interrupt);
}

SearchResult search_least_squares(const Residuals& residuals, const std::vector<double>& start, const std::vector<double>& lower,
                                  const std::vector<double>& upper, const std::vector<bool>& logarithmic, const SearchSettings& settings,
                                  const std::function<void(const SearchProgress&)>& progress, const std::atomic<bool>* interrupt) {
  const Objective unused = [](const std::vector<double>&) { return 0.0; };
  return search_with(unused, &residuals, start, lower, upper, logarithmic, settings, progress, interrupt);
}

}  // namespace rheo::runtime
