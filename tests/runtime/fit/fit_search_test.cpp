// The search strategy of `rheo fit` (runtime/fit/fit_search.hpp) on objectives whose minimum is
// known in closed form: reproducibility per seed, the evaluation budget, the sampling box,
// Ctrl-C (the interrupt flag), the deadline and the named global algorithms followed by the polish.
#include "runtime/fit/fit_search.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/core/evaluation_context.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace fit_search_test {

using namespace rheo::runtime;

namespace {

// A convex quadratic with its minimum at (1.2, -0.7, 2.5), inside the box [-4, 4]^3; minimum 0.5.
double bowl(const std::vector<double>& z) {
  const double a = z[0] - 1.2, b = z[1] + 0.7, c = z[2] - 2.5;
  return 0.5 + a * a + 4.0 * b * b + 0.25 * c * c + 0.5 * a * b;
}
const std::vector<double> bowl_start{-2.0, 3.0, 0.0}, bowl_lower{-4.0, -4.0, -4.0}, bowl_upper{4.0, 4.0, 4.0};
const std::vector<bool> linear3{false, false, false};

// Records every point the search evaluates, with the stage it was evaluated in.
struct Recorder {
  std::vector<std::vector<double>> points;
  std::vector<double> values;
  std::vector<std::string> stages;

  Objective objective() {
    return [this](const std::vector<double>& z) {
      points.push_back(z);
      values.push_back(bowl(z));
      return values.back();
    };
  }
  std::function<void(const SearchProgress&)> progress() {
    return [this](const SearchProgress& p) { stages.emplace_back(p.stage); };
  }
};

void check_at_bowl_minimum(const SearchResult& r, double tolerance) {
  CAPTURE(r.status);
  CAPTURE(r.evaluations);
  CHECK(std::abs(r.z[0] - 1.2) < tolerance);
  CHECK(std::abs(r.z[1] + 0.7) < tolerance);
  CHECK(std::abs(r.z[2] - 2.5) < tolerance);
  CHECK(r.value - 0.5 < tolerance * tolerance * 10.0);
  CHECK_FALSE(r.interrupted);
}

}  // namespace

TEST_CASE("the same seed gives bitwise the same search, for the default strategy and a stochastic global one") {
  for (const std::optional<Algorithm> algorithm : {std::optional<Algorithm>{}, std::optional<Algorithm>{Algorithm::crs2}}) {
    SearchSettings s;
    s.algorithm = algorithm;
    s.seed = 17;
    s.max_evaluations = 3000;
    Recorder first, second;
    const SearchResult a = search(first.objective(), bowl_start, bowl_lower, bowl_upper, linear3, s);
    const SearchResult b = search(second.objective(), bowl_start, bowl_lower, bowl_upper, linear3, s);
    CHECK(a.z == b.z);  // exact comparison: bitwise the same doubles
    CHECK(a.value == b.value);
    CHECK(a.evaluations == b.evaluations);
    CHECK(first.points == second.points);  // evaluation for evaluation
    check_at_bowl_minimum(a, 1e-6);
  }
}

TEST_CASE("a different seed samples different points but reaches the same minimum of a convex problem") {
  SearchSettings s;
  s.seed = 1;
  Recorder one, two;
  const SearchResult a = search(one.objective(), bowl_start, bowl_lower, bowl_upper, linear3, s);
  s.seed = 2;
  const SearchResult b = search(two.objective(), bowl_start, bowl_lower, bowl_upper, linear3, s);
  // The sample (the second evaluation, after the start) depends on the seed's random shift.
  REQUIRE(one.points.size() > 1);
  REQUIRE(two.points.size() > 1);
  CHECK(one.points[0] == two.points[0]);
  CHECK(one.points[1] != two.points[1]);
  check_at_bowl_minimum(a, 1e-6);
  check_at_bowl_minimum(b, 1e-6);
  for (std::size_t j = 0; j < 3; ++j) CHECK(std::abs(a.z[j] - b.z[j]) < 2e-6);
}

TEST_CASE("the default strategy samples max(10 n, 40) points a decade either side of the start (log) or a quarter of the bounds (linear)") {
  // z0 = ln p with bounds of two decades below and five above; z1 linear in [-4, 4]; z2 log
  // with its box clipped by the upper bound.
  const std::vector<double> start{std::log(1.0), 1.0, std::log(50.0)};
  const std::vector<double> lower{std::log(0.01), -4.0, std::log(1.0)};
  const std::vector<double> upper{std::log(1e5), 4.0, std::log(100.0)};
  Recorder r;
  SearchSettings s;
  s.max_evaluations = 500;
  search(r.objective(), start, lower, upper, {true, false, true}, s, r.progress());
  REQUIRE(r.stages.size() == r.points.size());
  CHECK(r.stages.front() == "start");
  CHECK(r.points.front() == start);
  const double decade = std::log(10.0);
  const double box_lo[] = {start[0] - decade, 1.0 - 2.0, start[2] - decade};
  const double box_hi[] = {start[0] + decade, 1.0 + 2.0, std::log(100.0)};
  int samples = 0;
  for (std::size_t k = 0; k < r.points.size(); ++k) {
    if (r.stages[k] != "sample") continue;
    ++samples;
    for (std::size_t j = 0; j < 3; ++j) {
      CHECK(r.points[k][j] >= box_lo[j]);
      CHECK(r.points[k][j] <= box_hi[j]);
    }
  }
  CHECK(samples == 40);  // max(10 * 3, 40)
  CHECK(std::count(r.stages.begin(), r.stages.end(), "polish") > 0);
}

TEST_CASE("the evaluation budget holds for every strategy and budget, with no slack") {
  const std::optional<Algorithm> strategies[] = {std::nullopt,        Algorithm::bobyqa, Algorithm::sbplx, Algorithm::neldermead,
                                                 Algorithm::direct_l, Algorithm::crs2,   Algorithm::isres, Algorithm::mlsl};
  for (const auto& algorithm : strategies)
    for (const int budget : {1, 2, 3, 7, 40, 101, 600}) {
      CAPTURE(algorithm ? static_cast<int>(*algorithm) : -1);
      CAPTURE(budget);
      SearchSettings s;
      s.algorithm = algorithm;
      s.max_evaluations = budget;
      Recorder r;
      const SearchResult result = search(r.objective(), bowl_start, bowl_lower, bowl_upper, linear3, s);
      CHECK(result.evaluations == static_cast<int>(r.points.size()));
      CHECK(result.evaluations <= budget);
      CHECK(result.evaluations >= 1);  // the start is always evaluated
      // The reported point is the best one evaluated, and its value is the objective there.
      const auto best = std::min_element(r.values.begin(), r.values.end());
      CHECK(result.value == *best);
      CHECK(result.z == r.points[static_cast<std::size_t>(best - r.values.begin())]);
    }
}

TEST_CASE("the interrupt flag stops the search at the next evaluation with the best point so far") {
  for (const std::optional<Algorithm> algorithm : {std::optional<Algorithm>{}, std::optional<Algorithm>{Algorithm::direct_l}})
    for (const int after : {1, 5, 60, 120}) {
      CAPTURE(after);
      std::atomic<bool> interrupt{false};
      Recorder r;
      const Objective base = r.objective();
      const Objective objective = [&](const std::vector<double>& z) {
        const double v = base(z);
        if (static_cast<int>(r.points.size()) == after) interrupt.store(true);  // Ctrl-C during this evaluation
        return v;
      };
      SearchSettings s;
      s.algorithm = algorithm;
      const SearchResult result = search(objective, bowl_start, bowl_lower, bowl_upper, linear3, s, {}, &interrupt);
      CHECK(result.interrupted);
      CHECK(result.status == "interrupted");
      CHECK(result.evaluations == after);
      REQUIRE(r.points.size() == static_cast<std::size_t>(after));
      const auto best = std::min_element(r.values.begin(), r.values.end());
      CHECK(result.value == *best);
      CHECK(result.z == r.points[static_cast<std::size_t>(best - r.values.begin())]);
    }
}

TEST_CASE("an interrupt set before the search still evaluates the start and returns it") {
  std::atomic<bool> interrupt{true};
  Recorder r;
  const SearchResult result = search(r.objective(), bowl_start, bowl_lower, bowl_upper, linear3, {}, {}, &interrupt);
  CHECK(result.interrupted);
  CHECK(result.evaluations == 1);
  CHECK(result.z == bowl_start);
  CHECK(result.value == bowl(bowl_start));
}

TEST_CASE("a named global algorithm followed by the polish finds the minimum of a bounded quadratic") {
  for (const Algorithm algorithm : {Algorithm::direct_l, Algorithm::crs2}) {
    CAPTURE(static_cast<int>(algorithm));
    SearchSettings s;
    s.algorithm = algorithm;
    s.max_evaluations = 2000;
    Recorder r;
    const SearchResult inside = search(r.objective(), bowl_start, bowl_lower, bowl_upper, linear3, s, r.progress());
    check_at_bowl_minimum(inside, 1e-6);
    CHECK(std::count(r.stages.begin(), r.stages.end(), "global") > 0);
    CHECK(std::count(r.stages.begin(), r.stages.end(), "polish") > 0);
    CHECK(std::count(r.stages.begin(), r.stages.end(), "sample") == 0);
    // With z2 <= 1 the minimum lies on the face z2 = 1, where the (a, b) part is still minimal
    // at a = b = 0 (it does not couple to c): z = (1.2, -0.7, 1), value 0.5 + 0.25 * 1.5^2.
    const SearchResult bounded = search(bowl, {0.0, 0.0, 0.0}, bowl_lower, {4.0, 4.0, 1.0}, linear3, s);
    // The local stages stop at a relative change of 1e-9 in the objective, which leaves z
    // within about sqrt(1e-9) of the minimiser; the value is quadratically closer.
    CHECK(std::abs(bounded.z[0] - 1.2) < 1e-4);
    CHECK(std::abs(bounded.z[1] + 0.7) < 1e-4);
    CHECK(bounded.z[2] == doctest::Approx(1.0).epsilon(1e-9));
    CHECK(bounded.value == doctest::Approx(0.5 + 0.25 * 1.5 * 1.5).epsilon(1e-10));
  }
}

TEST_CASE("non-finite objective values are counted in every stage, the start's included, and never become the best") {
  int nan_count = 0;
  const Objective holed = [&](const std::vector<double>& z) {
    if (std::hypot(z[0] + 2.0, z[1] - 3.0, z[2]) < 1.0) {  // a ball around the start (-2, 3, 0)
      ++nan_count;
      return std::nan("");
    }
    return bowl(z);
  };
  const SearchResult r = search(holed, bowl_start, bowl_lower, bowl_upper, linear3, {});
  CHECK(nan_count > 1);  // the start and some samples
  CHECK(r.non_finite == nan_count);
  check_at_bowl_minimum(r, 1e-6);
}

TEST_CASE("a point that cannot be simulated (NumericalError) is rejected like NaN, and the first message is kept") {
  int failures = 0;
  const Objective failing = [&](const std::vector<double>& z) {
    if (z[0] < -1.5) throw NumericalError("cannot simulate " + std::to_string(++failures));
    return bowl(z);
  };
  const SearchResult r = search(failing, bowl_start, bowl_lower, bowl_upper, linear3, {});
  CHECK(failures > 1);  // the start (z0 = -2) and some samples
  CHECK(r.non_finite == failures);
  CHECK(r.first_failure == "cannot simulate 1");
  check_at_bowl_minimum(r, 1e-6);
  const SearchResult clean = search(bowl, bowl_start, bowl_lower, bowl_upper, linear3, {});
  CHECK(clean.first_failure.empty());
}

TEST_CASE("when no trial point is finite the search says so, for every strategy, instead of returning a point") {
  int calls = 0;
  const Objective nowhere = [&](const std::vector<double>&) -> double {
    if (++calls % 2) throw NumericalError("cannot simulate anywhere");
    return std::numeric_limits<double>::infinity();
  };
  for (const auto algorithm : {std::optional<Algorithm>{}, std::optional<Algorithm>{Algorithm::direct_l}}) {
    SearchSettings s;
    s.algorithm = algorithm;
    s.max_evaluations = 200;
    calls = 0;
    CHECK_THROWS_WITH_AS(search(nowhere, bowl_start, bowl_lower, bowl_upper, linear3, s),
                         doctest::Contains("trial points of the search gave a finite objective (first failure: cannot simulate anywhere)"),
                         NumericalError);
    CHECK(calls > 40);  // the start, the samples or the global stage, and the local searches ran
  }
}

TEST_CASE("extra starts are searched from, and a start that is already optimal is kept") {
  SearchSettings s;
  s.extra_starts = {{1.2, -0.7, 2.5}};
  s.max_evaluations = 60;  // too few to get there from the start alone
  Recorder r;
  const SearchResult result = search(r.objective(), bowl_start, bowl_lower, bowl_upper, linear3, s);
  CHECK(std::find(r.points.begin(), r.points.end(), s.extra_starts.front()) != r.points.end());
  CHECK(result.value == 0.5);
  CHECK(result.z == s.extra_starts.front());
}

TEST_CASE("a deadline stops the search with the best point so far, leaving room for the reserved evaluations") {
  using Clock = std::chrono::steady_clock;
  Recorder r;
  const Objective base = r.objective();
  const Objective slow = [&](const std::vector<double>& z) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    return base(z);
  };
  SUBCASE("a deadline already passed: the start only") {
    SearchSettings s;
    s.deadline = Clock::now() - std::chrono::seconds(1);
    const SearchResult result = search(slow, bowl_start, bowl_lower, bowl_upper, linear3, s);
    CHECK(result.out_of_time);
    CHECK(result.status == "TIME_LIMIT_REACHED");
    CHECK(result.evaluations == 1);
    CHECK(result.z == bowl_start);
  }
  SUBCASE("room for some evaluations, none started that the time left cannot cover") {
    SearchSettings s;
    const auto deadline = Clock::now() + std::chrono::milliseconds(60);
    s.deadline = deadline;
    const SearchResult result = search(slow, bowl_start, bowl_lower, bowl_upper, linear3, s);
    const auto finished = Clock::now();
    CHECK(result.out_of_time);
    CHECK(result.evaluations > 1);
    CHECK(result.evaluations < 40);  // 2 ms each at least
    CHECK(finished < deadline + std::chrono::milliseconds(200));
    const auto best = std::min_element(r.values.begin(), r.values.end());
    CHECK(result.value == *best);
  }
  SUBCASE("a reserve the time left cannot cover: the start only") {
    SearchSettings s;
    s.deadline = Clock::now() + std::chrono::milliseconds(60);
    s.reserve_evaluations = 1000;  // 2 s at 2 ms each
    const SearchResult result = search(slow, bowl_start, bowl_lower, bowl_upper, linear3, s);
    CHECK(result.out_of_time);
    CHECK(result.evaluations == 1);
  }
  SUBCASE("no deadline: the search runs to its own end") {
    const SearchResult result = search(r.objective(), bowl_start, bowl_lower, bowl_upper, linear3, {});
    CHECK_FALSE(result.out_of_time);
    check_at_bowl_minimum(result, 1e-4);
  }
}

namespace {

// The bowl as residuals: 0.5 + a^2 + 4 b^2 + 0.25 c^2 + 0.5 a b = sum r_i^2 (a Cholesky factor).
std::vector<double> bowl_residuals(const std::vector<double>& z) {
  const double a = z[0] - 1.2, b = z[1] + 0.7, c = z[2] - 2.5;
  return {std::sqrt(0.5), a + 0.25 * b, std::sqrt(4.0 - 0.0625) * b, 0.5 * c};
}

}  // namespace

TEST_CASE("the least-squares search: Levenberg-Marquardt reaches the bowl's minimum in fewer evaluations than BOBYQA") {
  const SearchResult ls = search_least_squares(bowl_residuals, bowl_start, bowl_lower, bowl_upper, linear3, {});
  check_at_bowl_minimum(ls, 1e-6);
  CHECK(std::abs(bowl(ls.z) - ls.value) < 1e-14);  // the value is the sum of squares
  const SearchResult plain = search(bowl, bowl_start, bowl_lower, bowl_upper, linear3, {});
  CHECK(ls.evaluations < plain.evaluations);
  SUBCASE("a named algorithm searches the sum of squares with NLopt instead") {
    SearchSettings s;
    s.algorithm = Algorithm::bobyqa;
    const SearchResult named = search_least_squares(bowl_residuals, bowl_start, bowl_lower, bowl_upper, linear3, s);
    check_at_bowl_minimum(named, 1e-4);
    CHECK(named.evaluations == plain.evaluations);  // the same search as search() of the sum
  }
}

TEST_CASE("the least-squares search keeps the budget, the best point and the interrupt as the plain one does") {
  for (const int budget : {1, 2, 3, 7, 40, 101, 600}) {
    CAPTURE(budget);
    SearchSettings s;
    s.max_evaluations = budget;
    std::vector<std::vector<double>> points;
    std::vector<double> values;
    const Residuals recorded = [&](const std::vector<double>& z) {
      points.push_back(z);
      values.push_back(bowl(z));
      return bowl_residuals(z);
    };
    const SearchResult result = search_least_squares(recorded, bowl_start, bowl_lower, bowl_upper, linear3, s);
    CHECK(result.evaluations == static_cast<int>(points.size()));
    CHECK(result.evaluations <= budget);
    const auto best = std::min_element(values.begin(), values.end());
    CHECK(std::abs(result.value - *best) < 1e-14);
    CHECK(result.z == points[static_cast<std::size_t>(best - values.begin())]);
  }
  std::atomic<bool> interrupt{false};
  int calls = 0;
  const Residuals stopping = [&](const std::vector<double>& z) {
    if (++calls == 9) interrupt.store(true);
    return bowl_residuals(z);
  };
  SearchSettings no_samples;
  no_samples.samples = 0;  // the interrupt comes inside a Levenberg-Marquardt search
  const SearchResult stopped = search_least_squares(stopping, bowl_start, bowl_lower, bowl_upper, linear3, no_samples, {}, &interrupt);
  CHECK(stopped.interrupted);
  CHECK(stopped.evaluations == 9);
}

TEST_CASE("the least-squares search: columns and trial steps start from the periodic states of the accepted point") {
  // Each call's evaluation context (evaluation_context.hpp): a single evaluation of
  // Levenberg-Marquardt (its start, a trial step) records; the columns of a Jacobian start
  // from what the point they difference about recorded, and so do the trial steps after them;
  // the rest (the first evaluation, the samples) neither records nor starts warm.
  struct Call {
    std::vector<double> z;
    EvaluationContext context;
  };
  for (int threads : {1, 2}) {
    CAPTURE(threads);
    std::mutex mutex;
    std::vector<Call> calls;
    const Residuals observed = [&](const std::vector<double>& z) {
      const std::lock_guard lock(mutex);
      calls.push_back({z, evaluation_context()});
      return bowl_residuals(z);
    };
    SearchSettings s;
    s.threads = threads;
    s.samples = 3;
    search_least_squares(observed, bowl_start, bowl_lower, bowl_upper, linear3, s);
    CHECK(calls.front().context.record == nullptr);
    CHECK(calls.front().context.start == nullptr);
    const Call* single = nullptr;
    const PwlWarmStarts* accepted = nullptr;
    int columns = 0, warm_trials = 0, singles = 0;
    for (const Call& call : calls) {
      if (call.context.record != nullptr) {  // a single evaluation: from the accepted point's states, if any yet
        ++singles;
        if (call.context.start != nullptr) {
          ++warm_trials;
          CHECK(call.context.start == accepted);
        }
        CHECK(call.context.start != call.context.record);
        single = &call;
        continue;
      }
      if (call.context.start == nullptr) continue;
      ++columns;  // a column: about the last single evaluation, which is now the accepted point
      REQUIRE(single != nullptr);
      CHECK(call.context.start == single->context.record);
      accepted = single->context.record;
      int moved = 0;
      for (std::size_t j = 0; j < call.z.size(); ++j) moved += call.z[j] != single->z[j];
      CHECK(moved == 1);
    }
    CHECK(singles >= 2);
    CHECK(warm_trials >= 1);
    CHECK(columns >= 3);
  }
}

TEST_CASE("an extra start equal to the start is searched from once, and a sample takes its place") {
  for (const bool duplicate : {false, true}) {
    CAPTURE(duplicate);
    std::vector<std::vector<double>> points;
    const Residuals recorded = [&](const std::vector<double>& z) {
      points.push_back(z);
      return bowl_residuals(z);
    };
    SearchSettings s;
    s.samples = 10;
    s.starts = 3;
    s.extra_starts = {duplicate ? bowl_start : std::vector<double>{0.5, 0.5, 0.5}};
    search_least_squares(recorded, bowl_start, bowl_lower, bowl_upper, linear3, s);
    // Each local search evaluates its start first, right after the previous search (or the
    // samples): the start itself appears once after sampling, the extra start once (when new).
    const auto after_samples = points.begin() + 11;
    CHECK(std::count(after_samples, points.end(), bowl_start) == 1);
    if (!duplicate) CHECK(std::count(after_samples, points.end(), std::vector<double>{0.5, 0.5, 0.5}) == 1);
  }
}

}  // namespace fit_search_test
