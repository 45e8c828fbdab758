#include "runtime/fit/fit_search.hpp"

#include "runtime/closed_form/pwl_warm_start.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/core/evaluation_context.hpp"
#include "runtime/fit/levenberg_marquardt.hpp"
#include "runtime/fit/search_tracker.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

namespace rheo::runtime {
namespace {

struct LocalBudgetSpent {};

// A Levenberg-Marquardt local search that has not converged after this many Jacobians is
// crawling along a curved valley; its budget serves the next start better.
constexpr int kMaxLocalIterations = 50;

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

// Uniform in [0, 1) from one output x of the engine: x / 2^64 (the double nearest x, scaled),
// or the largest double below 1 where x rounds up to 2^64. The engine's outputs are specified
// bit for bit, std::uniform_real_distribution's mapping is not (libc++ and MSVC differ from
// libstdc++); this is libstdc++'s, so a seed samples the same shift with every standard library.
double unit_interval(std::mt19937_64& random) {
  const double u = static_cast<double>(random()) / 18446744073709551616.0;
  return u < 1.0 ? u : std::nextafter(1.0, 0.0);
}

// SAMPLES points of the box a decade (log coordinates) or a quarter of the range (linear ones)
// either side of START, within the bounds, on a Halton sequence shifted by SEED (Cranley-
// Patterson rotation), each with its objective value (evaluated as one batch): best first,
// non-finite values last.
std::vector<std::pair<double, std::vector<double>>> sample_box(Tracker& tracker, const std::vector<double>& start, const std::vector<double>& lower,
                                                               const std::vector<double>& upper, const std::vector<bool>& logarithmic, int samples,
                                                               unsigned long seed) {
  const std::size_t n = start.size();
  std::mt19937_64 random(seed);
  const std::vector<unsigned> primes = first_primes(n);
  std::vector<double> shift(n), box_lo(n), box_hi(n);
  for (std::size_t j = 0; j < n; ++j) {
    shift[j] = unit_interval(random);
    const double half = logarithmic[j] ? std::log(10.0) : 0.25 * (upper[j] - lower[j]);
    box_lo[j] = std::max(lower[j], start[j] - half);
    box_hi[j] = std::min(upper[j], start[j] + half);
  }
  std::vector<std::vector<double>> points(static_cast<std::size_t>(std::max(0, samples)), std::vector<double>(n));
  for (std::size_t s = 0; s < points.size(); ++s)
    for (std::size_t j = 0; j < n; ++j) {
      const double t = std::fmod(radical_inverse(static_cast<unsigned long>(s + 1), primes[j]) + shift[j], 1.0);
      points[s][j] = box_lo[j] + t * (box_hi[j] - box_lo[j]);
    }
  const std::vector<double> values = tracker.values(points);
  std::vector<std::pair<double, std::vector<double>>> sampled;
  for (std::size_t s = 0; s < points.size(); ++s) sampled.emplace_back(values[s], std::move(points[s]));
  // Non-finite samples sort last (NaN would break the ordering std::sort relies on).
  auto key = [](double v) { return std::isfinite(v) ? v : std::numeric_limits<double>::infinity(); };
  std::stable_sort(sampled.begin(), sampled.end(), [&](const auto& a, const auto& b) { return key(a.first) < key(b.first); });
  return sampled;
}

// Levenberg-Marquardt from FROM on the tracker's residuals, within BUDGET evaluations; the
// NLopt-style status. A start whose residuals are not finite ends it at once.
std::string least_squares_local(Tracker& tracker, const std::vector<double>& from, int budget, const std::vector<double>& lower,
                                const std::vector<double>& upper, const SearchSettings& settings, std::size_t residual_count) {
  const int first = tracker.evaluations();
  LeastSquaresProblem problem;
  // Warm starts (closed_form/pwl_warm_start.hpp). Every single evaluation (the start, a trial
  // step) records the periodic states of its event-driven subtrees. A batch whose points each
  // move one coordinate of the last single evaluation's x is a differenced Jacobian's columns
  // about the accepted point (levenberg_marquardt evaluates that last): they start their
  // shootings from its states, and so do the trial steps that follow, until the next Jacobian.
  // Every column and trial starts from the accepted point's states, so the results do not
  // depend on the threads.
  std::array<PwlWarmStarts, 2> stores;
  PwlWarmStarts* latest = &stores[0];       // the last single evaluation's
  const PwlWarmStarts* accepted = nullptr;  // the accepted point's (sealed)
  Eigen::VectorXd latest_x;
  bool latest_accepted = false;    // latest_x is the accepted point (its states in *accepted)
  if (!tracker.has_residuals()) {  // phi alone, each Jacobian reduced (search_least_squares_by_value)
    problem.value = [&](const Eigen::VectorXd& x) {
      if (tracker.evaluations() - first >= budget) throw LocalBudgetSpent{};
      return tracker(std::vector<double>(x.data(), x.data() + x.size()));
    };
    problem.residual_count = residual_count;
  }
  problem.residuals = [&](const Eigen::VectorXd& x) {
    if (tracker.evaluations() - first >= budget) throw LocalBudgetSpent{};
    latest->clear();
    latest_x = x;
    latest_accepted = false;
    const EvaluationScope scope({latest, accepted});
    const std::vector<double>& r = tracker.residuals(std::vector<double>(x.data(), x.data() + x.size()));
    return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size())));
  };
  const auto about_latest = [&](const std::vector<Eigen::VectorXd>& xs) {
    return std::all_of(xs.begin(), xs.end(),
                       [&](const Eigen::VectorXd& x) { return x.size() == latest_x.size() && (x.array() != latest_x.array()).count() <= 1; });
  };
  // As the calls above one after another: the local budget first, then the tracker's stops.
  problem.residuals_batch = [&](const std::vector<Eigen::VectorXd>& xs) {
    const auto left = static_cast<std::size_t>(std::max(0, budget - (tracker.evaluations() - first)));
    std::vector<std::vector<double>> zs;
    for (std::size_t k = 0; k < std::min(left, xs.size()); ++k) zs.emplace_back(xs[k].data(), xs[k].data() + xs[k].size());
    const bool columns = about_latest(xs);
    if (columns && !latest_accepted) {  // the last single evaluation is the accepted point
      latest->seal();
      accepted = latest;
      latest = latest == &stores[0] ? &stores[1] : &stores[0];
      latest_accepted = true;
    }
    const EvaluationScope scope({nullptr, columns ? accepted : nullptr});
    const std::vector<std::vector<double>> rs = tracker.residuals(zs);
    if (zs.size() < xs.size()) throw LocalBudgetSpent{};
    std::vector<Eigen::VectorXd> out;
    for (const std::vector<double>& r : rs) out.emplace_back(Eigen::Map<const Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size())));
    return out;
  };
  if (tracker.has_jacobian())
    problem.jacobian = [&](const Eigen::VectorXd& x, const Eigen::VectorXd&) {
      if (tracker.evaluations() - first >= budget) throw LocalBudgetSpent{};
      return tracker.jacobian(std::vector<double>(x.data(), x.data() + x.size()));
    };
  if (tracker.has_reduced_jacobian())  // a long history's Jacobian, never held whole (history_jacobian.hpp)
    problem.reduced_jacobian = [&](const Eigen::VectorXd& x, const Eigen::VectorXd& steps) -> std::optional<LeastSquaresProblem::Reduced> {
      if (tracker.evaluations() - first + (steps.array() != 0.0).count() > budget) throw LocalBudgetSpent{};
      std::optional<ReducedJacobian> reduced = tracker.reduced_jacobian(std::vector<double>(x.data(), x.data() + x.size()),
                                                                        std::vector<double>(steps.data(), steps.data() + steps.size()));
      if (!reduced) return std::nullopt;
      return LeastSquaresProblem::Reduced{std::move(reduced->r), std::move(reduced->c)};
    };
  LevenbergMarquardtSettings lm;
  lm.max_iterations = std::min(budget, kMaxLocalIterations);
  lm.step_tolerance = settings.tolerance;
  lm.crawl_tolerance = settings.crawl_tolerance;
  lm.decrease_tolerance = 1e-9;  // as the NLopt local stages' relative f tolerance
  // Steps of 1e-6 max(|z|, 1): for z = ln p a relative change of 1e-6 to ~1e-5 in the parameter,
  // above the event-driven and time-stepped paths' convergence noise, below the response's curvature.
  lm.difference_step = 1e-6;
  lm.threads = settings.threads;
  auto to_eigen = [](const std::vector<double>& v) { return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size())); };
  try {
    return levenberg_marquardt(problem, to_eigen(from), to_eigen(lower), to_eigen(upper), lm).status;
  } catch (const LocalBudgetSpent&) {
    return "MAXEVAL_REACHED";
  } catch (const NumericalError&) {
    return "NO_FINITE_START";
  }
}

// RESIDUAL_COUNT: m where the objective is a sum of m squares given by its value alone
// (search_least_squares_by_value), else unused.
SearchResult search_with(const Objective& objective, const Residuals* residuals, const std::vector<double>& start, const std::vector<double>& lower,
                         const std::vector<double>& upper, const std::vector<bool>& logarithmic, const SearchSettings& settings,
                         const std::function<void(const SearchProgress&)>& progress, const std::atomic<bool>* interrupt,
                         std::size_t residual_count = 0) {
  const std::size_t n = start.size();
  Tracker tracker(objective, residuals, progress, interrupt, settings);
  const Objective tracked = [&](const std::vector<double>& z) { return tracker(z); };
  SearchResult result;
  auto remaining = [&] { return tracker.limit() - tracker.evaluations(); };
  auto local = [&](const std::vector<double>& from, int budget, Algorithm algorithm) {
    if ((tracker.has_residuals() || residual_count > 0) && !settings.algorithm) {
      result.status = least_squares_local(tracker, from, std::max(1, budget), lower, upper, settings, residual_count);
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
      const auto sampled = sample_box(tracker, start, lower, upper, logarithmic, std::max(0, std::min(wanted_samples, remaining() / 4)),
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

SearchResult search_least_squares_by_value(const Objective& objective, std::size_t residual_count, const std::vector<double>& start,
                                           const std::vector<double>& lower, const std::vector<double>& upper, const std::vector<bool>& logarithmic,
                                           const SearchSettings& settings, const std::function<void(const SearchProgress&)>& progress,
                                           const std::atomic<bool>* interrupt) {
  if (!settings.reduced_jacobian || residual_count == 0)
    throw std::logic_error("search_least_squares_by_value: a reduced Jacobian and the number of residuals are needed");
  return search_with(objective, nullptr, start, lower, upper, logarithmic, settings, progress, interrupt, residual_count);
}

}  // namespace rheo::runtime
