// The specimen-D harmonic grid of the data (182 points, 0.2-3 mm x 1-51 Hz), evaluated by the
// closed-form periodic state (the default) and by time stepping to steady state; and the
// hydrobushing grid (147 points) of the coupled model of examples/hydrobushing_fit.rheo at its
// start values (a slider-capped fluid column beside the rubber), by the exact event-driven
// periodic state (solver = auto) and time-stepped as that fit block asks (fixed, 128 steps per
// cycle, periodicity 1e-6; an approximation), also as a Jacobian column warm-started from the
// base point's periodic states; and one trial of diagnose's backlash screen.
#include "bench_support.hpp"
#include "runtime/closed_form/pwl_warm_start.hpp"
#include "runtime/core/evaluation_context.hpp"
#include "runtime/fit/fit_scoring.hpp"
#include "runtime/fit/objective.hpp"
#include "lang/frontend.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <stdexcept>
#include <string>

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

// Each iteration the grid of DATA through the next of NETWORKS (in turn, so that nothing kept for
// one serves the next); counter cycles_per_point.
void grid_in_turn(benchmark::State& state, const std::vector<runtime::Network>& networks, const runtime::FitDataSet& data,
                  const runtime::HarmonicOptions& options) {
  std::vector<runtime::HarmonicPoint> points;
  std::size_t next = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(points = runtime::simulate_at(networks[next], data.harmonic(), options));
    next = (next + 1) % networks.size();
  }
  double cycles = 0.0;
  for (const auto& p : points) cycles += p.cycles;
  state.counters["cycles_per_point"] = cycles / static_cast<double>(points.size());
}

// Each evaluation a network with parameter `changed` scaled by 1 + 1e-12 k (k = 0..63 in
// turn), as from one evaluation of a fit to the next.
void hydrobushing(benchmark::State& state, runtime::SolverChoice solver, const char* changed = "fluid.k2") {
  const runtime::Network network = runtime::Network::compile(bench::example_model("hydrobushing_fit.rheo", "coupled"));
  const auto data = bench::example_data("hydrobushing_harmonic.csv");
  runtime::HarmonicOptions options;
  options.solver = solver;
  if (solver == runtime::SolverChoice::fixed) options.steps_per_cycle = 128, options.tolerance = 1e-6;
  std::vector<runtime::Network> networks;
  const auto& parameters = network.model().parameters;
  const auto found = std::find_if(parameters.begin(), parameters.end(), [&](const lang::Parameter& q) { return q.path == changed; });
  if (found == parameters.end()) throw std::logic_error(std::string("hydrobushing_fit.rheo: no parameter ") + changed);
  for (int k = 0; k < 64; ++k) {
    std::vector<double> values = network.parameters();
    values[static_cast<std::size_t>(found - parameters.begin())] *= 1.0 + 1e-12 * k;
    networks.push_back(network.with_parameters(values));
  }
  grid_in_turn(state, networks, data, options);
}

// A parameter of the fluid branch changes: nothing the event path keeps for a branch (its
// modes' drive-independent parts, its solves) serves the next evaluation.
void BM_Hydrobushing_CoupledGrid_EventDriven(benchmark::State& state) { hydrobushing(state, runtime::SolverChoice::automatic); }
// Only a parameter outside the branch changes (the Maxwell arm's stiffness), as in a Jacobian
// column of a fit: the branch's solves are restored (pwl_periodic.hpp), the rest recomputed.
void BM_Hydrobushing_CoupledGrid_EventDriven_OtherParameter(benchmark::State& state) {
  hydrobushing(state, runtime::SolverChoice::automatic, "m1.k");
}
void BM_Hydrobushing_CoupledGrid_Fixed128(benchmark::State& state) { hydrobushing(state, runtime::SolverChoice::fixed); }

// A Jacobian column of a fit that moves a parameter of the fluid branch (fluid.k2 by 1e-6,
// and by 1e-12 k more each evaluation so that nothing kept serves the next): every point's
// shooting starts from the base point's periodic state (closed_form/pwl_warm_start.hpp).
void BM_Hydrobushing_CoupledGrid_EventDriven_WarmColumn(benchmark::State& state) {
  const runtime::Network network = runtime::Network::compile(bench::example_model("hydrobushing_fit.rheo", "coupled"));
  const auto data = bench::example_data("hydrobushing_harmonic.csv");
  const runtime::HarmonicOptions options;
  runtime::PwlWarmStarts base;
  {
    const runtime::EvaluationScope scope({&base, nullptr});
    runtime::simulate_at(network, data.harmonic(), options);
  }
  base.seal();
  const auto& parameters = network.model().parameters;
  const auto k2 = static_cast<std::size_t>(
      std::find_if(parameters.begin(), parameters.end(), [](const lang::Parameter& q) { return q.path == "fluid.k2"; }) - parameters.begin());
  std::vector<runtime::Network> networks;
  for (int k = 0; k < 64; ++k) {
    std::vector<double> values = network.parameters();
    values[k2] *= (1.0 + 1e-6) * (1.0 + 1e-12 * k);
    networks.push_back(network.with_parameters(values));
  }
  const runtime::EvaluationScope scope({nullptr, &base});
  grid_in_turn(state, networks, data, options);
}

// One trial of `rheo diagnose`'s backlash screen: free play (0.2 mm) in front of a friction
// element (arg 0) or a Maxwell element (arg 1), alone, on the hydrobushing grid (147 points) by
// the event path, the play's width changed each evaluation (by 1e-6 relative) as from trial to
// trial, so nothing kept for the branch serves the next.
void BM_Backlash_Trial_Grid(benchmark::State& state) {
  std::vector<runtime::Network> networks;
  for (int k = 0; k < 16; ++k) {
    const std::string w = std::to_string(0.2 * (1.0 + 1e-6 * k));
    const std::string text = state.range(0) == 0 ? "model probe {\nseries added {\ngap play (width = " + w +
                                                       " mm, center = 0 mm)\nfriction f (k = 100 N/mm, uy = 50 um)\n}\n}\n"
                                                 : "model probe {\nseries added {\ngap play (width = " + w +
                                                       " mm, center = 0 mm)\nmaxwell m (k = 100 N/mm, tau = 3 ms)\n}\n}\n";
    const lang::Program program = lang::compile_source("<probe>", text);
    networks.push_back(runtime::Network::compile(program.models.front()));
  }
  const auto data = bench::example_data("hydrobushing_harmonic.csv");
  runtime::HarmonicOptions options;
  grid_in_turn(state, networks, data, options);
}

}  // namespace

BENCHMARK(BM_Hydrobushing_CoupledGrid_EventDriven)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Hydrobushing_CoupledGrid_EventDriven_OtherParameter)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Hydrobushing_CoupledGrid_EventDriven_WarmColumn)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Hydrobushing_CoupledGrid_Fixed128)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SpecimenD_Grid_ClosedForm)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SpecimenD_Grid_TimeStepping2048)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Backlash_Trial_Grid)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
