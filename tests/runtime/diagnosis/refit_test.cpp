// The refit budgets of rheo diagnose: counted work, not time, so that results do not depend on
// the machine.
#include "runtime/diagnosis/refit.hpp"
#include "runtime/diagnosis/candidate_model.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <algorithm>

namespace refit_test {

using namespace rheo;

TEST_CASE("diagnose refits: a local search is Levenberg-Marquardt from one point within its budget, without statistics") {
  runtime::FitSettings base;
  base.statistics = true;
  base.search.starts = 5;
  base.search.extra_starts = {{1.0, 2.0}};
  const runtime::FitSettings local = runtime::diagnosis::local_search(base, 123);
  CHECK_FALSE(local.search.algorithm.has_value());  // the default local method: LM on the residuals
  CHECK(local.search.starts == 1);
  CHECK(local.search.samples == 0);
  CHECK(local.search.extra_starts.empty());
  CHECK(local.search.max_evaluations == 123);
  CHECK_FALSE(local.statistics);
  CHECK_FALSE(local.yeoh_start_from_history);
}

TEST_CASE("diagnose refits: the evaluations afforded follow the work of one evaluation, within the floor and the cap") {
  runtime::HistoryData history;
  history.path = "h.csv";
  for (int k = 0; k <= 1000; ++k) {
    history.drive.time.push_back(k * 1e-3);
    history.drive.displacement.push_back(0.0);
    history.force.push_back(0.0);
  }
  history.force_scale = 1.0;
  const std::vector<runtime::FitDataSet> data{runtime::FitDataSet{"h.csv", 1.0, history, {}}};
  runtime::diagnosis::DiagnoseSettings s;
  s.refit_work = 1e4;
  s.max_evaluations = 1000;
  // Root-parallel: 0.05 per sample, 1001 samples: 50.05 per evaluation, 1e4 / 50.05 = 199.8 afforded.
  const auto flat = test::network_from("model m { spring k (k = 1 N/mm) maxwell x (k = 1 N/mm, tau = 1 s) }", "m");
  CHECK(runtime::diagnosis::affordable_evaluations(flat, data, s, 0) == 199);
  CHECK(runtime::diagnosis::affordable_evaluations(flat, data, s, 500) == 500);  // the floor
  s.refit_work = 1e9;
  CHECK(runtime::diagnosis::affordable_evaluations(flat, data, s, 0) == 1000);  // the cap
}

// The start-sensitivity of a fluid column's refit (issue #24): the uncoupled hydrobushing fit
// ends at points of equal err (2.375e-2) whose friction and Maxwell elements differ; from this
// one the column's refit used to stop at err 9.15e-3 (its stage 2 from the best of stage 1, a
// BOBYQA search, spent its budget far from the basin, and only the start's search moved), where
// from others it reached 6.9e-3. Both searches of stage 2 now descend the residuals, and the
// column reaches the basin the polished diagnosis ends in (6.87e-3 to 6.97e-3 over disturbed
// data, docs/performance.md) to within 10 %.
TEST_CASE("diagnose refits: a fluid column refitted onto an uncoupled fit that stops it elsewhere still reaches the basin") {
  const std::string fitted_text = R"(model uncoupled {
  spring   rubber (k = 818.617503642 N/mm in [10, 10000])
  maxwell  m1 (k = 10000 N/mm in [1, 10000], tau = 0.02867524609082 ms in [0.01, 10000])
  maxwell  m2 (k = 145.58728379127 N/mm in [1, 10000], tau = 7.293247436026 ms in [0.01, 10000])
  friction f1 (k = 10000 N/mm in [1, 10000], uy = 0.7170561871034 um in [0.1, 10000])
  friction f2 (k = 112.32667373823 N/mm in [1, 10000], uy = 0.7435343641957 um in [0.1, 10000])
  friction f3 (k = 1.0393385979507 N/mm in [1, 10000], uy = 1.906701532426 um in [0.1, 10000])
  friction f4 (k = 207.19485647394 N/mm in [1, 10000], uy = 108.8015613738 um in [0.1, 10000])
}
)";
  const std::vector<runtime::FitDataSet> data{runtime::read_fit_data(std::string(RHEO_EXAMPLES_DIR) + "/data/hydrobushing_harmonic.csv", 1.0)};
  runtime::diagnosis::DiagnoseSettings s;  // as diagnose gives its refits (diagnose_bench.cpp)
  s.fit.score.method = runtime::FitMethod::exact;
  s.fit.score.harmonic.steps_per_cycle = 128;
  s.fit.score.harmonic.tolerance = 1e-6;
  const lang::Program fitted_program = lang::compile_source("base.rheo", fitted_text);
  const lang::CheckedModel& fitted = *fitted_program.find_model("uncoupled");
  // The column as the screen sizes it on this fit: fy = 18.92 N, k = 228.8 N/mm, 20.5 Hz, zeta 0.089.
  runtime::diagnosis::Trial column;
  column.effect = runtime::diagnosis::Effect::coupled_amplitude_frequency;
  column.shape = runtime::diagnosis::Shape::capped_column;
  column.stiffness = 228.8, column.slip = 18.92 / 228.8, column.frequency = 20.5, column.damping_ratio = 0.089;
  const runtime::diagnosis::DataScales scales = runtime::diagnosis::data_scales(data);
  const lang::Program candidate_program = lang::compile_source(
      "base.rheo", runtime::diagnosis::with_trial(fitted_text, fitted, column, "coupled", scales.bounds, "candidate"));
  const lang::CheckedModel& candidate = *candidate_program.find_model("uncoupled");
  std::vector<int> kept, added;
  for (std::size_t i = 0; i < candidate.parameters.size(); ++i)
    if (candidate.parameters[i].free) (candidate.parameters[i].path.starts_with("coupled.") ? added : kept).push_back(static_cast<int>(i));
  REQUIRE(kept.size() == 13);
  REQUIRE(added.size() == 4);  // fy, k, b, c
  const runtime::FitResult refit = runtime::diagnosis::staged_refit(runtime::Network::compile(candidate), kept, added, data, s);
  MESSAGE("column refit: err " << refit.err << " in " << refit.evaluations << " evaluations");
  CHECK(refit.err < 1.1 * 6.97e-3);
  CHECK(refit.err > 0.9 * 6.87e-3);  // no better than the polished diagnosis: the noise leaves ~6e-3
}

}  // namespace refit_test
