#include "runtime/diagnosis/refit.hpp"

#include "runtime/diagnosis/global_look.hpp"
#include "runtime/fit/fit_scoring.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/protocols/solver_choice.hpp"
#include "runtime/stepping/tree_solver.hpp"

#include <algorithm>
#include <chrono>
#include <optional>

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
// A cycle followed event to event (closed_form/pwl_periodic.hpp) counts 300 units: what it cost
// (about 100 us) when the unit was set. Shooting on the half-period map with modes reused across
// points made it about 13 us (docs/performance.md); the count was kept, so that the refits'
// budgets, and their results, did not change with the speed.
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

// The free stiffnesses of NETWORK's linear springs in its root parallel block among KEPT: the
// linear stiffness a new element may need taken back from the model (free play engaging at the
// larger amplitudes stiffens the data where the fitted springs had stiffened the model
// everywhere), which stage 1 frees beside the new parameters (as the screen refits the linear
// stiffness beside every trial, screen.cpp).
std::vector<int> root_spring_stiffnesses(const Network& network, const std::vector<int>& kept) {
  std::vector<int> out;
  for (const auto& e : network.model().root.children)
    if (e.kind == lang::ElementKind::spring && std::find(kept.begin(), kept.end(), e.parameters[0]) != kept.end()) out.push_back(e.parameters[0]);
  return out;
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
  f.search.algorithm.reset();
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
  const auto started = std::chrono::steady_clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(); };
  // Stage 1: the global look, then a local search of the new parameters and the root springs'
  // stiffnesses from each of its best points.
  const int samples = std::max(settings.global_samples * n_added, std::min(affordable / 4, 4 * settings.global_samples * n_added));
  const std::vector<SampledStart> starts = global_look(start, added, data, settings.fit.score, samples, settings.global_starts);
  std::vector<int> first_free = added;
  for (int i : root_spring_stiffnesses(start, kept)) first_free.push_back(i);
  std::sort(first_free.begin(), first_free.end());
  const int per_start = thorough ? affordable / (2 * static_cast<int>(starts.size())) : kLocalJacobians * (static_cast<int>(first_free.size()) + 1);
  std::optional<FitResult> stage1;
  int evaluations = samples + 1, non_finite = 0;
  for (std::size_t k = 0; k < starts.size(); ++k) {
    FitSettings first = local_search(settings.fit, per_start);
    if (settings.fit.time_limit) {
      first.time_limit = (*settings.fit.time_limit / 2.0 - seconds()) / static_cast<double>(starts.size() - k);  // stage 2 gets half
      if (*first.time_limit <= 0.0 && stage1) break;
      first.time_limit = std::max(1e-3, *first.time_limit);
    }
    FitResult local = fit(start.with_parameters(starts[k].values), first_free, data, first);
    evaluations += local.evaluations, non_finite += local.non_finite;
    const bool interrupted = local.interrupted;
    if (!stage1 || local.objective < stage1->objective) stage1 = std::move(local);
    if (interrupted) {
      stage1->interrupted = true;
      break;
    }
  }
  stage1->evaluations = evaluations, stage1->non_finite = non_finite, stage1->wall_seconds = seconds();
  stage1->start_values = start.parameters();
  if (stage1->interrupted || kept.empty()) return std::move(*stage1);
  std::vector<int> all = kept;
  all.insert(all.end(), added.begin(), added.end());
  std::sort(all.begin(), all.end());
  // Stage 2 from the best of stage 1, and from the screened element as it was sized: the model's
  // own elements may have taken up part of the missing effect, so that the new element helps
  // only once they give it back, which the new parameters alone cannot find.
  std::optional<FitResult> stage2;
  const std::vector<Network> froms{stage1->network, start};
  for (std::size_t k = 0; k < froms.size(); ++k) {
    FitSettings second = local_search(settings.fit, std::max(affordable / 4, kLocalJacobians * (n_all + 1)));
    if (settings.fit.time_limit) {
      second.time_limit = (*settings.fit.time_limit - seconds()) / static_cast<double>(froms.size() - k);
      if (*second.time_limit <= 0.0 && stage2) break;
      second.time_limit = std::max(1e-3, *second.time_limit);
    }
    FitResult local = fit(froms[k], all, data, second);
    const int spent = local.evaluations + (stage2 ? stage2->evaluations : 0);
    const bool interrupted = local.interrupted, time_limited = local.time_limited || (stage2 && stage2->time_limited);
    if (!stage2 || local.objective < stage2->objective) stage2 = std::move(local);
    stage2->evaluations = spent, stage2->time_limited = time_limited;
    if (interrupted) {
      stage2->interrupted = true;
      break;
    }
  }
  // The better search, where its budget ran out while it still descended, continues once from
  // where it stopped with the same budget, ending where a Jacobian's step gains less than
  // kPolishCrawl of the objective (as the polish): a search of 17 parameters reached its basin in
  // the tenth or the eleventh Jacobian as the damped steps' rounding went (refit_test.cpp).
  if (stage2->status == "MAXEVAL_REACHED" && !stage2->interrupted && !stage2->time_limited) {
    FitSettings more = local_search(settings.fit, std::max(affordable / 4, kLocalJacobians * (n_all + 1)));
    more.search.crawl_tolerance = kPolishCrawl;
    if (settings.fit.time_limit) more.time_limit = std::max(1e-3, *settings.fit.time_limit - seconds());
    FitResult further = fit(stage2->network, all, data, more);
    const int spent = further.evaluations + stage2->evaluations;
    const bool interrupted = further.interrupted, time_limited = further.time_limited;
    if (further.objective < stage2->objective) stage2 = std::move(further);
    stage2->evaluations = spent, stage2->interrupted = stage2->interrupted || interrupted;
    stage2->time_limited = stage2->time_limited || time_limited;
  }
  stage2->time_limited = stage2->time_limited || stage1->time_limited;
  stage2->start_values = stage1->start_values;
  stage2->yeoh_started = stage1->yeoh_started;
  stage2->evaluations += stage1->evaluations;
  stage2->non_finite += stage1->non_finite;
  stage2->wall_seconds = seconds();
  return std::move(*stage2);
}

}  // namespace rheo::runtime::diagnosis
