// The specimen-D harmonic grid of the data (182 points, 0.2-3 mm x 1-51 Hz), evaluated by the
// closed-form periodic state (the default) and by time stepping to steady state.
#include "bench_support.hpp"
#include "runtime/fit/fit_scoring.hpp"

#include <benchmark/benchmark.h>

namespace {

using namespace rheo;

void grid(benchmark::State& state, runtime::SteadyState steady_state) {
  const runtime::Network network = runtime::Network::compile(bench::example_model("specimen_d.rheo", "specimen_d"));
  const runtime::FitDataSet data = bench::example_data("specimen_D_harmonic.csv");
  runtime::HarmonicOptions options;
  options.steady_state = steady_state;
  for (auto _ : state) {
    const runtime::Prediction p = runtime::predict(network, data, runtime::FitMethod::exact, options, nullptr);
    benchmark::DoNotOptimize(p.points.data());
  }
  state.counters["points"] = static_cast<double>(data.harmonic().size());
}

void BM_SpecimenD_Grid_ClosedForm(benchmark::State& state) { grid(state, runtime::SteadyState::closed_form); }
void BM_SpecimenD_Grid_TimeStepping2048(benchmark::State& state) { grid(state, runtime::SteadyState::time_stepping); }

}  // namespace

BENCHMARK(BM_SpecimenD_Grid_ClosedForm)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SpecimenD_Grid_TimeStepping2048)->Unit(benchmark::kMillisecond);
