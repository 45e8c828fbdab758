// A long displacement history through the specimen-D model (yeoh + Maxwell + 6 friction: 8
// elements): 1e6 steps of a two-sine drive (1.5 Hz, 2 mm plus 23 Hz, 0.1 mm; dt = 0.1 ms), streamed
// into one 4096-sample buffer as `rheo simulate` streams a history (run_history.hpp), so that the
// figure is the stepping's: a History of 1e6 samples copies the drive and clears its force column
// each run, 24 MB of fresh pages, which on a virtual machine took 80 % of the time.
// Reported: time per run and ns per element-step. And the error control's cost
// (stepping/drive_stepper.hpp): a standard linear solid (a spring in series with a spring beside
// a dashpot) whose internal time c/(k1 + k2) is /0: 10 times, /1: a tenth of the 1 ms sample, on
// 1e5 samples of a two-sine drive (3 Hz, 0.3 mm plus 41 Hz, 0.05 mm), with the control and
// without it (one step a sample); counters: steps per sample, time per sample.
#include "bench_support.hpp"
#include "lang/frontend.hpp"
#include "runtime/protocols/run_history.hpp"
#include "runtime/stepping/drive_stepper.hpp"

#include <fmt/format.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

namespace {

using namespace rheo;

void BM_SpecimenD_History_1e6Steps(benchmark::State& state) {
  const runtime::Network network = runtime::Network::compile(bench::example_model("specimen_d.rheo", "specimen_d"));
  constexpr int steps = 1'000'000;
  constexpr double dt = 1e-4;
  runtime::Drive drive;
  drive.time.resize(steps + 1);
  drive.displacement.resize(steps + 1);
  for (int k = 0; k <= steps; ++k) {
    const double t = k * dt;
    drive.time[static_cast<std::size_t>(k)] = t;
    drive.displacement[static_cast<std::size_t>(k)] = 2.0 * std::sin(2 * std::numbers::pi * 1.5 * t) +
                                                      0.1 * std::sin(2 * std::numbers::pi * 23.0 * t);
  }
  std::vector<double> buffer(4096);
  for (auto _ : state) {
    runtime::HistoryForceStream stream(network, drive);
    while (stream.next(buffer) > 0) benchmark::DoNotOptimize(buffer.data());
  }
  const double elements = 8.0;
  state.counters["ns_per_element_step"] = benchmark::Counter(static_cast<double>(state.iterations()) * steps * elements,
                                                             benchmark::Counter::kIsRate | benchmark::Counter::kInvert, benchmark::Counter::kIs1000);
}

void standard_linear_solid(benchmark::State& state, double tolerance) {
  const double c = state.range(0) == 0 ? 2.5 : 0.025;  // N*s/mm against k1 + k2 = 250 N/mm: 10 ms or 0.1 ms
  const lang::Program program = lang::compile_source(
      "bench.rheo", fmt::format("model m {{ series {{ spring (k = 200 N/mm) parallel {{ spring (k = 50 N/mm) dashpot (c = {} N*s/mm) }} }} }}", c));
  const runtime::Network network = runtime::Network::compile(*program.find_model("m"));
  constexpr int samples = 100'000;
  std::vector<double> u(samples + 1);
  for (int k = 0; k <= samples; ++k) {
    const double t = 1e-3 * k;
    u[static_cast<std::size_t>(k)] = 0.3 * std::sin(2 * std::numbers::pi * 3.0 * t) + 0.05 * std::sin(2 * std::numbers::pi * 41.0 * t);
  }
  long steps = 0;
  for (auto _ : state) {
    runtime::DriveStepper stepper(network, false, tolerance);
    benchmark::DoNotOptimize(stepper.start(0.0, u[0]));
    for (int k = 1; k <= samples; ++k) benchmark::DoNotOptimize(stepper.step(1e-3 * k, u[static_cast<std::size_t>(k)]));
    steps += stepper.steps();
  }
  const auto runs = static_cast<double>(state.iterations());
  state.counters["steps_per_sample"] = static_cast<double>(steps) / (runs * samples);
  state.counters["s_per_sample"] = benchmark::Counter(runs * samples, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_StandardLinearSolid_History_Controlled(benchmark::State& state) { standard_linear_solid(state, runtime::DriveStepper::kDefaultTolerance); }
void BM_StandardLinearSolid_History_OneStep(benchmark::State& state) { standard_linear_solid(state, 0.0); }

}  // namespace

BENCHMARK(BM_SpecimenD_History_1e6Steps)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StandardLinearSolid_History_Controlled)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StandardLinearSolid_History_OneStep)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
