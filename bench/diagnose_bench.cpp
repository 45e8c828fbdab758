// `rheo diagnose examples/hydrobushing_fit.rheo --block 1` in process: the uncoupled model on
// the hydrobushing grid (147 points), with the command line's settings (128 steps per cycle
// where a candidate is time-stepped, periodicity 1e-6, every bounded parameter free, 3
// candidates refitted). Reported: wall time, the effect's gap before and after.
#include "runtime/diagnosis/diagnose.hpp"
#include "bench_support.hpp"

#include <benchmark/benchmark.h>

#include <fstream>
#include <iterator>

namespace {

using namespace rheo;

void BM_Hydrobushing_Diagnose(benchmark::State& state) {
  const std::string file = std::string(RHEO_EXAMPLES_DIR) + "/hydrobushing_fit.rheo";
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::vector<runtime::FitDataSet> data{bench::example_data("hydrobushing_harmonic.csv")};
  runtime::diagnosis::DiagnoseSettings settings;
  settings.fit.score.harmonic.steps_per_cycle = 128;
  settings.fit.score.harmonic.tolerance = 1e-6;
  runtime::diagnosis::Diagnosis d;
  for (auto _ : state) d = runtime::diagnosis::diagnose({file, text, "uncoupled"}, data, settings);
  state.counters["gap_before"] = d.gap_before;
  state.counters["gap_after"] = d.gap_after;
}

}  // namespace

BENCHMARK(BM_Hydrobushing_Diagnose)->Unit(benchmark::kSecond)->Iterations(1);
