// `rheo fit` of specimens D and C from the generic starts of examples/specimen_{d,c}_fit.rheo
// with the default strategy and settings, on their measured harmonic grids, and of the Prony
// series of examples/prony_fit.rheo on its master curve. Reported: wall time
// per fit, evaluations and the err (6.1) reached.
#include "bench_support.hpp"
#include "runtime/fit/fit.hpp"

#include <benchmark/benchmark.h>

namespace {

using namespace rheo;

void fit(benchmark::State& state, const char* file, const char* model, const char* csv, runtime::FitMethod method) {
  const runtime::Network start = runtime::Network::compile(bench::example_model(file, model));
  const std::vector<runtime::FitDataSet> data{bench::example_data(csv)};
  runtime::FitSettings settings;
  settings.score.method = method;
  runtime::FitResult result{.network = start};
  for (auto _ : state) result = runtime::fit(start, runtime::bounded_parameters(start), data, settings);
  state.counters["evaluations"] = result.evaluations;
  state.counters["err"] = result.err;
}

// The Prony series of examples/prony_fit.rheo: 21 stiffnesses, every tau held, 161 points over 18
// decades: one bounded least-squares solve (separable_fit.hpp), standard errors included.
void BM_Prony20_FixedTau_Fit(benchmark::State& state) {
  fit(state, "prony_fit.rheo", "prony", "prony_master_curve.csv", runtime::FitMethod::exact);
}

void BM_SpecimenD_Fit(benchmark::State& state) {
  fit(state, "specimen_d_fit.rheo", "specimen_d", "specimen_D_harmonic.csv", runtime::FitMethod::exact);
}
void BM_SpecimenC_Fit(benchmark::State& state) {
  fit(state, "specimen_c_fit.rheo", "specimen_c", "specimen_C_harmonic.csv", runtime::FitMethod::exact);
}

// #23's coupled bushing: 14 free parameters, a nested slider + Maxwell arm (event-driven
// periodic states), 147 points, default settings from the example's generic start.
void BM_CoupledBushing_Fit(benchmark::State& state) {
  fit(state, "coupled_bushing_fit.rheo", "coupled", "coupled_bushing_harmonic.csv", runtime::FitMethod::exact);
}

}  // namespace

BENCHMARK(BM_Prony20_FixedTau_Fit)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SpecimenD_Fit)->Unit(benchmark::kSecond)->Iterations(3);
BENCHMARK(BM_SpecimenC_Fit)->Unit(benchmark::kSecond)->Iterations(3);
BENCHMARK(BM_CoupledBushing_Fit)->Unit(benchmark::kSecond)->Iterations(1);
