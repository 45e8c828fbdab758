// Speed-up of --threads on the two evaluations a fit repeats (Arg = threads):
//  - the hydrobushing harmonic grid (147 points) of the coupled model of
//    examples/hydrobushing_fit.rheo at its start values, as its fit block evaluates it
//    (solver = fixed, 128 steps per cycle, periodicity tolerance 1e-6): time stepped;
//  - one evaluation of the specimen-D grid (182 closed-form points, about a microsecond each) and
//    the whole specimen-D fit of examples/specimen_d_fit.rheo;
//  - the whole coupled-bushing fit of examples/coupled_bushing_fit.rheo (#23: 14 free
//    parameters, 147 event-driven points), default settings.
// In a fit the Jacobians' columns and the samples are evaluated side by side, one evaluation per
// thread (runtime/fit/search_tracker.hpp); single evaluations spread their points.
#include "bench_support.hpp"
#include "runtime/fit/fit.hpp"
#include "runtime/fit/objective.hpp"

#include <benchmark/benchmark.h>

namespace {

using namespace rheo;

void BM_Hydrobushing_CoupledGrid_Threads(benchmark::State& state) {
  const runtime::Network network = runtime::Network::compile(bench::example_model("hydrobushing_fit.rheo", "coupled"));
  const auto data = bench::example_data("hydrobushing_harmonic.csv");
  runtime::HarmonicOptions options;
  options.solver = runtime::SolverChoice::fixed;
  options.steps_per_cycle = 128;
  options.tolerance = 1e-6;
  options.threads = static_cast<int>(state.range(0));
  std::vector<runtime::HarmonicPoint> points;
  for (auto _ : state) benchmark::DoNotOptimize(points = runtime::simulate_at(network, data.harmonic(), options));
  double cycles = 0.0;
  for (const auto& p : points) cycles += p.cycles;
  state.counters["cycles_per_point"] = cycles / static_cast<double>(points.size());
  state.counters["time_per_step"] = benchmark::Counter(cycles * options.steps_per_cycle,
                                                       benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// One evaluation of the specimen-D fit: its 182 closed-form points at the start values.
void BM_SpecimenD_Grid_Threads(benchmark::State& state) {
  const runtime::Network network = runtime::Network::compile(bench::example_model("specimen_d_fit.rheo", "specimen_d"));
  const auto data = bench::example_data("specimen_D_harmonic.csv");
  runtime::HarmonicOptions options;
  options.threads = static_cast<int>(state.range(0));
  std::vector<runtime::HarmonicPoint> points;
  for (auto _ : state) benchmark::DoNotOptimize(points = runtime::simulate_at(network, data.harmonic(), options));
}

void fit_on_threads(benchmark::State& state, const char* file, const char* model, const char* csv) {
  const runtime::Network start = runtime::Network::compile(bench::example_model(file, model));
  const std::vector<runtime::FitDataSet> data{bench::example_data(csv)};
  runtime::FitSettings settings;
  settings.score.harmonic.threads = static_cast<int>(state.range(0));
  runtime::FitResult result{.network = start};
  for (auto _ : state) result = runtime::fit(start, runtime::bounded_parameters(start), data, settings);
  state.counters["evaluations"] = result.evaluations;
  state.counters["err"] = result.err;
}

void BM_SpecimenD_Fit_Threads(benchmark::State& state) { fit_on_threads(state, "specimen_d_fit.rheo", "specimen_d", "specimen_D_harmonic.csv"); }

void BM_CoupledBushing_Fit_Threads(benchmark::State& state) {
  fit_on_threads(state, "coupled_bushing_fit.rheo", "coupled", "coupled_bushing_harmonic.csv");
}

}  // namespace

BENCHMARK(BM_Hydrobushing_CoupledGrid_Threads)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_SpecimenD_Grid_Threads)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SpecimenD_Fit_Threads)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->Iterations(3);
BENCHMARK(BM_CoupledBushing_Fit_Threads)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1);
