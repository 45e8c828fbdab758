// Batches of independent evaluations (runtime/fit/search_tracker.hpp): a search on several
// threads is the search on one, evaluation for evaluation, wherever its budget cuts a batch and
// wherever points cannot be evaluated; and a batch's evaluations do run at once.
#include "runtime/fit/fit_search.hpp"

#include "runtime/core/errors.hpp"

#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

namespace search_tracker_test {

using namespace rheo::runtime;

namespace {

// Rosenbrock's valley in five coordinates as eight residuals. Some points cannot be evaluated,
// so that samples, trial steps and Jacobian columns meet them: z4 < -0.3 cannot be simulated
// (NumericalError), nor can z1 just above 1 (the start's forward step in z1: that column is
// differenced backwards), and z0 < -1.3 gives NaN.
std::vector<double> valley(const std::vector<double>& z) {
  if (z[4] < -0.3 || (z[1] > 1.0 && z[1] < 1.0 + 1e-5)) throw NumericalError("outside the model's range");
  if (z[0] < -1.3) return std::vector<double>(8, std::nan(""));
  std::vector<double> r;
  for (std::size_t i = 0; i + 1 < z.size(); ++i) {
    r.push_back(10.0 * (z[i + 1] - z[i] * z[i]));
    r.push_back(1.0 - z[i]);
  }
  return r;
}

const std::vector<double> start{-1.2, 1.0, -1.2, 1.0, 0.5}, lower(5, -2.0), upper(5, 2.0);
const std::vector<bool> linear5(5, false);

struct Run {
  SearchResult result;
  std::vector<std::tuple<int, double, std::string>> progress;  // every evaluation's report, in order
};

Run run(int threads, int budget, int samples) {
  SearchSettings s;
  s.threads = threads;
  s.max_evaluations = budget;
  s.samples = samples;
  s.seed = 3;
  Run out;
  out.result = search_least_squares(valley, start, lower, upper, linear5, s,
                                    [&](const SearchProgress& p) { out.progress.emplace_back(p.evaluations, p.best, p.stage); });
  return out;
}

}  // namespace

TEST_CASE("a least-squares search on 2 or 3 threads makes the evaluations of 1 thread, wherever the budget cuts a batch") {
  for (const int samples : {-1, 7}) {
    for (const int budget : {1, 2, 6, 13, 47, 120, 20000}) {
      CAPTURE(samples);
      CAPTURE(budget);
      const Run one = run(1, budget, samples);
      CHECK(one.result.evaluations == static_cast<int>(one.progress.size()));
      for (const int threads : {2, 3}) {
        CAPTURE(threads);
        const Run several = run(threads, budget, samples);
        CHECK(several.result.z == one.result.z);
        CHECK(several.result.value == one.result.value);
        CHECK(several.result.evaluations == one.result.evaluations);
        CHECK(several.result.non_finite == one.result.non_finite);
        CHECK(several.result.first_failure == one.result.first_failure);
        CHECK(several.result.status == one.result.status);
        CHECK(several.progress == one.progress);
      }
    }
  }
  // The valley's holes are met, so the rejected evaluations are part of what is compared.
  const Run full = run(1, 20000, -1);
  CHECK(full.result.non_finite > 0);
  CHECK(full.result.first_failure == "outside the model's range");
  CHECK(std::abs(full.result.z[0] - 1.0) < 1e-4);
}

TEST_CASE("a batch's evaluations run at once on two threads") {
  // Each of the first sampled points waits (at most 5 s) until another evaluation is running too.
  std::atomic<int> running{0}, calls{0};
  std::atomic<bool> overlapped{false};
  const Residuals waiting = [&](const std::vector<double>& z) {
    const int call = ++calls;
    ++running;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (call > 1 && call <= 5 && !overlapped && std::chrono::steady_clock::now() < until) {
      if (running.load() >= 2) overlapped = true;
      std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
    --running;
    return valley(z);
  };
  SearchSettings s;
  s.threads = 2;
  s.samples = 4;
  s.max_evaluations = 30;
  search_least_squares(waiting, start, lower, upper, linear5, s);
  CHECK(overlapped.load());
}

}  // namespace search_tracker_test
