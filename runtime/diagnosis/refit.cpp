#include "runtime/diagnosis/refit.hpp"

#include "runtime/fit/fit_scoring.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/protocols/solver_choice.hpp"
#include "runtime/stepping/tree_solver.hpp"

#include <algorithm>

namespace rheo::runtime::diagnosis {
namespace {

// Work of one evaluation of NETWORK in fixed time steps of a nested network, counted on one
// prediction: a time-stepped harmonic point costs the cycles it took to its periodic state
// times the steps per cycle, a history sample one step, and a closed-form point 10. A step
// under IDA (whose steps solve a DAE with Newton iterations) counts 10. A step of a network
// whose elements all sit in the root parallel block counts 0.05 (its kernel is one update per
// element, ~20 ns a step), of one whose subtrees step without iteration (linear and
// capped-linear chains, tree_solver.hpp) 0.3 (~0.13 us), of others 1 (the nested Newton
// iterations, 0.3-3 us; docs/performance.md), and a point stepped event to event 300 per
// cycle its shooting followed. Counted, not timed, so that budgets, and
// results, do not depend on the machine.
// A cycle followed event to event (closed_form/pwl_periodic.hpp: 64 grid steps of a small
// matrix, the located switches and, once, the first harmonic) costs about 100 us, 300 units.
constexpr double kEventCycleWork = 300.0;

double evaluation_work(const Network& network, const std::vector<FitDataSet>& data, const HarmonicOptions& options) {
  const Topology& t = network.topology();
  const double step_cost = uses_sundials(network, options.solver) ? 10.0 : t.subtrees.empty() ? 0.05 : steps_without_iteration(t) ? 0.3 : 1.0;
  double work = 0.0;
  for (const auto& set : data) {
    if (!set.is_harmonic()) {
      work += step_cost * static_cast<double>(set.history().force.size());
      continue;
    }
    const bool exact = uses_closed_form(network, options);
    for (const HarmonicPoint& point : predict(network, set, FitMethod::exact, options, nullptr).points)
      work += point.cycles == 0 ? 10.0 : exact ? kEventCycleWork * point.cycles : step_cost * point.cycles * options.steps_per_cycle;
  }
  return work;
}

}  // namespace

int affordable_evaluations(const Network& network, const std::vector<FitDataSet>& data, const DiagnoseSettings& s, int floor) {
  const double per_evaluation = std::max(1.0, evaluation_work(network, data, s.fit.score.harmonic));
  return static_cast<int>(std::clamp(s.refit_work / per_evaluation, static_cast<double>(floor), static_cast<double>(s.max_evaluations)));
}

FitSettings local_search(const FitSettings& base, int evaluations) {
  FitSettings f = base;
  f.yeoh_start_from_history = false;
  f.statistics = false;
  f.search.algorithm = Algorithm::bobyqa;
  f.search.starts = 1;
  f.search.samples = 0;
  f.search.extra_starts.clear();
  f.search.max_evaluations = evaluations;
  return f;
}

FitResult staged_refit(const Network& start, const std::vector<int>& kept, const std::vector<int>& added, const std::vector<FitDataSet>& data,
                       const DiagnoseSettings& settings) {
  const int n_added = static_cast<int>(added.size()), n_all = n_added + static_cast<int>(kept.size());
  const int affordable = affordable_evaluations(start, data, settings, 0);
  const bool thorough = affordable >= settings.thorough_evaluations * (n_added + n_all);
  FitSettings first = local_search(settings.fit, thorough ? affordable / 2 : 2 * n_added + 1 + 15 * n_added);
  if (thorough) first.search.algorithm.reset(), first.search.starts = 3, first.search.samples = -1;
  FitResult stage1 = fit(start, added, data, first);
  if (stage1.interrupted || kept.empty()) return stage1;
  std::vector<int> all = kept;
  all.insert(all.end(), added.begin(), added.end());
  std::sort(all.begin(), all.end());
  FitResult stage2 = fit(stage1.network, all, data, local_search(settings.fit, thorough ? affordable / 2 : 2 * n_all + 1 + 4 * n_all));
  stage2.start_values = stage1.start_values;
  stage2.yeoh_started = stage1.yeoh_started;
  stage2.evaluations += stage1.evaluations;
  stage2.non_finite += stage1.non_finite;
  stage2.wall_seconds += stage1.wall_seconds;
  return stage2;
}

}  // namespace rheo::runtime::diagnosis
