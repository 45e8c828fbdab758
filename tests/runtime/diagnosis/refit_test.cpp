// The refit budgets of rheo diagnose: counted work, not time, so that results do not depend on
// the machine.
#include "runtime/diagnosis/refit.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

using namespace rheo;

TEST_CASE("diagnose refits: a local search is one BOBYQA run within its budget, without statistics") {
  runtime::FitSettings base;
  base.statistics = true;
  base.search.starts = 5;
  base.search.extra_starts = {{1.0, 2.0}};
  const runtime::FitSettings local = runtime::diagnosis::local_search(base, 123);
  CHECK(local.search.algorithm == runtime::Algorithm::bobyqa);
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
