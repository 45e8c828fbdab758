// A long displacement history through the specimen-D model (yeoh + Maxwell + 6 friction: 8
// elements): 1e6 steps of a two-sine drive (1.5 Hz, 2 mm plus 23 Hz, 0.1 mm; dt = 0.1 ms).
// Reported: time per run and ns per element-step.
#include "bench_support.hpp"
#include "runtime/protocols/run_history.hpp"

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
  for (auto _ : state) {
    const runtime::History h = runtime::run_history(network, drive, false);
    benchmark::DoNotOptimize(h.force.data());
  }
  const double elements = 8.0;
  state.counters["ns_per_element_step"] = benchmark::Counter(static_cast<double>(state.iterations()) * steps * elements,
                                                             benchmark::Counter::kIsRate | benchmark::Counter::kInvert, benchmark::Counter::kIs1000);
}

}  // namespace

BENCHMARK(BM_SpecimenD_History_1e6Steps)->Unit(benchmark::kMillisecond);
