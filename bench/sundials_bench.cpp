// SUNDIALS IDA against the fixed-step kernels on the networks that need it:
//  - the hydrobushing harmonic grid of examples/data (147 points, 0.1-2 mm x 1-41 Hz) of
//    examples/hydrobushing.rheo, each point from rest to steady state;
//  - a 60 s two-sine history (road 1.5 Hz x 1.5 mm + engine 31 Hz x 0.05 mm, sampled at 2 kHz)
//    on the same model.
// Reported: wall time, and for IDA its steps, residual evaluations and events (steps/s is
// steps / wall time). Fixed steps use 256 steps per cycle on the grid (0.2 % / 0.26 deg from the
// reference) and 2048 (0.05 % / 0.02 deg), and the drive's own samples on the history.
#include "bench_support.hpp"
#include "runtime/dae/dae_protocols.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/protocols/run_history.hpp"
#include "runtime/io/harmonic_data.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

namespace {

using namespace rheo;

runtime::Network hydrobushing() { return runtime::Network::compile(bench::example_model("hydrobushing.rheo", "hydrobushing")); }

void grid(benchmark::State& state, runtime::SolverChoice solver, int steps_per_cycle) {
  const runtime::Network network = hydrobushing();
  const auto data = runtime::read_harmonic_data(std::string(RHEO_EXAMPLES_DIR) + "/data/hydrobushing_reference.csv");
  runtime::HarmonicOptions options;
  options.solver = solver;
  options.steady_state = runtime::SteadyState::time_stepping;
  options.steps_per_cycle = steps_per_cycle;
  runtime::DaeStatistics total;
  double worst = 0.0;
  for (auto _ : state) {
    total = {};
    for (std::size_t i = 0; i < data.amplitude.size(); ++i) {
      runtime::DaeStatistics s;
      const auto p = solver == runtime::SolverChoice::sundials
                         ? runtime::dae_harmonic_point(network, data.amplitude[i], data.frequency[i], options, &s)
                         : runtime::simulate_harmonic_point(network, data.amplitude[i], data.frequency[i], options);
      total.steps += s.steps;
      total.residual_evaluations += s.residual_evaluations;
      total.events += s.events;
      worst = std::max(worst, std::abs(p.measures.stiffness / data.stiffness[i] - 1.0));
    }
  }
  state.counters["worst_stiffness_error"] = worst;
  if (solver == runtime::SolverChoice::sundials) {
    state.counters["ida_steps"] = static_cast<double>(total.steps);
    state.counters["ida_steps_per_s"] = benchmark::Counter(static_cast<double>(total.steps), benchmark::Counter::kIsIterationInvariantRate);
    state.counters["events"] = static_cast<double>(total.events);
  }
}

void BM_Hydrobushing_Grid_Sundials(benchmark::State& state) { grid(state, runtime::SolverChoice::sundials, 256); }
void BM_Hydrobushing_Grid_Fixed256(benchmark::State& state) { grid(state, runtime::SolverChoice::fixed, 256); }
void BM_Hydrobushing_Grid_Fixed2048(benchmark::State& state) { grid(state, runtime::SolverChoice::fixed, 2048); }

runtime::Drive road_and_engine() {
  runtime::Drive d{{0.0}, {0.0}};
  const double rate = 2000.0, duration = 60.0;
  for (int k = 1; k <= static_cast<int>(rate * duration); ++k) {
    const double t = k / rate;
    d.time.push_back(t);
    d.displacement.push_back(1.5 * std::sin(2 * std::numbers::pi * 1.5 * t) + 0.05 * std::sin(2 * std::numbers::pi * 31.0 * t));
  }
  return d;
}

void history(benchmark::State& state, runtime::SolverChoice solver) {
  const runtime::Network network = hydrobushing();
  const runtime::Drive drive = road_and_engine();
  runtime::DaeStatistics s;
  for (auto _ : state) {
    if (solver == runtime::SolverChoice::sundials) benchmark::DoNotOptimize(runtime::dae_history(network, drive, false, &s));
    else benchmark::DoNotOptimize(runtime::run_history(network, drive, false, solver));
  }
  if (solver == runtime::SolverChoice::sundials) {
    state.counters["ida_steps"] = static_cast<double>(s.steps);
    state.counters["ida_steps_per_s"] = benchmark::Counter(static_cast<double>(s.steps), benchmark::Counter::kIsIterationInvariantRate);
    state.counters["events"] = static_cast<double>(s.events);
  }
}

void BM_Hydrobushing_RoadEngine60s_Sundials(benchmark::State& state) { history(state, runtime::SolverChoice::sundials); }
void BM_Hydrobushing_RoadEngine60s_Fixed(benchmark::State& state) { history(state, runtime::SolverChoice::fixed); }

}  // namespace

BENCHMARK(BM_Hydrobushing_Grid_Sundials)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_Hydrobushing_Grid_Fixed256)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_Hydrobushing_Grid_Fixed2048)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_Hydrobushing_RoadEngine60s_Sundials)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_Hydrobushing_RoadEngine60s_Fixed)->Unit(benchmark::kSecond)->Iterations(1);
