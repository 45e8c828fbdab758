// Cost per fixed step of nested networks against their flat equivalents (issue #26 item 3: at
// most 10x) and of bouc_wen against a friction element (issue #24: at most 10x).
//  - the reproducers of tests/corpus/repro/backends/ that cost seconds per sample before the
//    global Newton solve (runtime/stepping/tree_newton.hpp): 03 gap + bouc_wen, 05 bouc_wen +
//    inerter behind a gap, 06 bouc_wen + yeoh + friction nested, 07 bouc_wen + Maxwell, 10
//    depth-8 nesting, 11 and 12 bouc_wen chains saturating in double (tens of ms a step before
//    their fix); each beside the same elements all in the model's parallel block;
//  - a lone friction element and a lone bouc_wen (its k and fy).
//  - depth 2 ... 8: a chain of Maxwell elements and blocks of friction elements nested `depth`
//    blocks below the model's body, innermost a bouc_wen (or a spring), against the same
//    elements all in the model's parallel block; the spring family also by the nested solve
//    (TreeStepPlan::global_newton = false), whose cost grows about 3^depth.
// Drive: the harmonic protocol's, u = A sin(2 pi f t) at f = 2 Hz with 2048 steps per cycle,
// A = Arg um (50: the gaps barely engage; 400: every bouc_wen saturates), after one cycle from
// rest. Reported per step: time (s_per_step), the global solve's member evaluations
// (evaluations_per_step) and the steps that fell back to the nested solve (fallbacks).
#include "lang/frontend.hpp"
#include "runtime/stepping/simulator.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace rheo;

std::string repro(const std::string& name) {
  std::ifstream in(std::string(RHEO_CORPUS_DIR) + "/repro/backends/" + name + ".rheo");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The reproducers' elements, each in the model's parallel block.
const char* const kFlat03 = R"(model m {
  bouc_wen (k = 942.461 N/mm, n = 4.49061, uy = 47.5779 um)
  spring (k = 239.639 N/mm)
})";
const char* const kFlat05 = R"(model m {
  spring (k = 174.508 N/mm)
  bouc_wen (k = 192.416 N/mm, n = 4.07668, uy = 53.6044 um)
  inerter (b = 1.22431 kg)
})";
const char* const kFlat06 = R"(model m {
  friction (k = 173.863 N/mm, fy = 8.2742 N)
  bouc_wen (k = 106.467 N/mm, n = 2.4487, fy = 9.32452 N)
  yeoh (D10 = 294.216 N/mm, D20 = -6.28247 N/mm^3, D30 = 0.528421 N/mm^5)
  yeoh (D10 = 136.721 N/mm, D20 = 11.5635 N/mm^3, D30 = 2.11757 N/mm^5)
})";
const char* const kFlat07 = R"(model m {
  bouc_wen (k = 61.8286 N/mm, n = 1.70764, fy = 2.85385 N)
  maxwell (k = 599.631 N/mm, c = 2.73345 N*s/mm)
})";
const char* const kFlat10 = R"(model m {
  spring (k = 85.6325 N/mm)
  maxwell (k = 230.818 N/mm, tau = 21.3296 ms)
  maxwell (k = 82.9547 N/mm, c = 0.207639 N*s/mm)
  maxwell (k = 24.8856 N/mm, tau = 7.58514 ms)
  inerter (b = 0.564727 kg)
  friction (k = 114.23 N/mm, uy = 26.576 um)
  friction (k = 146.809 N/mm, fy = 32.3679 N)
  friction (k = 380.166 N/mm, fy = 6.78928 N)
  spring (k = 10.6157 N/mm)
  maxwell (k = 81.5424 N/mm, tau = 5.89151 ms)
  spring (k = 113.919 N/mm)
  maxwell (k = 20.0432 N/mm, tau = 47.5925 ms)
  spring (k = 16.5952 N/mm)
  maxwell (k = 713.098 N/mm, tau = 11.5166 ms)
  spring (k = 258.933 N/mm)
  maxwell (k = 51.6768 N/mm, c = 0.244034 N*s/mm)
  spring (k = 433.339 N/mm)
})";
// The elements of reproducers 11 and 12 (differential seed 13, models 98 and 7), each in the
// model's parallel block.
const char* const kFlat11 = R"(model m {
  spring (k = 6390.35 N/mm)
  bouc_wen (k = 23.0303 N/mm, n = 3.51357, uy = 42.0732 um)
  bouc_wen (k = 986.695 N/mm, n = 3.33631, fy = 1.54232 N)
  poly_spring (k1 = 4251.24 N/mm, k2 = -94.3709 N/mm^2, k3 = 1.39742 N/mm^3)
  quadratic_dashpot (cq = 0.0129264 N*s^2/mm^2)
  dashpot (c = 0.622476 N*s/mm)
  maxwell (k = 1536.28 N/mm, tau = 187.504 ms)
})";
const char* const kFlat12 = R"(model m {
  bouc_wen (k = 10.3845 N/mm, n = 3.03517, uy = 25.7235 um)
  quadratic_dashpot (cq = 0.00913806 N*s^2/mm^2)
  bouc_wen (k = 281.07 N/mm, n = 2.04233, fy = 3.48572 N)
  yeoh (D10 = 2.14497 N/mm, D20 = -0.197078 N/mm^3, D30 = 0.161742 N/mm^5)
  spring (k = 1626.22 N/mm)
  bouc_wen (k = 394.563 N/mm, n = 1.35602, fy = 1.15369 N)
  bouc_wen (k = 540.701 N/mm, n = 1.57933, fy = 10.9988 N)
  quadratic_dashpot (cq = 0.00443241 N*s^2/mm^2)
})";
const char* const kFriction = "model m { friction (k = 61.8286 N/mm, fy = 2.85385 N) }";
const char* const kBoucWen = "model m { bouc_wen (k = 61.8286 N/mm, n = 1.70764, fy = 2.85385 N) }";

// The depth family: `depth` blocks below the model's body, from the outermost a series chain
// (a block in the body would merge with it), then parallel and series in turn.
std::string level(int depth, const std::string& inner, int i = 0) {
  if (i == depth) return inner;
  if (i % 2 == 0) return "series { maxwell (k = 400 N/mm, tau = 5 ms) " + level(depth, inner, i + 1) + " }";
  return "parallel { friction (k = 150 N/mm, fy = 3 N) " + level(depth, inner, i + 1) + " }";
}
std::string flat_level(int depth, const std::string& inner, int i = 0) {
  if (i == depth) return inner;
  return (i % 2 == 0 ? "maxwell (k = 400 N/mm, tau = 5 ms) " : "friction (k = 150 N/mm, fy = 3 N) ") + flat_level(depth, inner, i + 1);
}
const char* const kInnerBoucWen = "bouc_wen (k = 200 N/mm, n = 2, fy = 4 N)";
const char* const kInnerSpring = "spring (k = 300 N/mm)";
std::string deep(int depth, const char* inner, bool nested) {
  return "model m { spring (k = 100 N/mm) " + (nested ? level(depth, inner) : flat_level(depth, inner)) + " }";
}

// Steps one cycle of amplitude `amplitude_um` after one from rest; counters per step.
void cycles(benchmark::State& state, const std::string& source, double amplitude_um, bool global_newton = true) {
  const lang::Program program = lang::compile_source("bench.rheo", source);
  const runtime::Network network = runtime::Network::compile(*program.find_model("m"));
  const runtime::Simulator simulator(network);
  constexpr int n = 2048;
  runtime::StepPlan plan = runtime::StepPlan::make(network, 0.5 / n);
  plan.tree.global_newton = global_newton;
  std::vector<double> drive(n);
  for (int k = 0; k < n; ++k) drive[static_cast<std::size_t>(k)] = 1e-3 * amplitude_um * std::sin(2.0 * std::numbers::pi * (k + 1) / n);
  runtime::State a = simulator.rest_state(), b = a;
  auto cycle = [&] {
    for (double u : drive) {
      benchmark::DoNotOptimize(simulator.step(plan, a, u, b));
      std::swap(a, b);
    }
    a.u = 0.0;
  };
  cycle();
  const runtime::NewtonWork start = plan.tree.work;
  long steps = 0;
  for (auto _ : state) {
    cycle();
    steps += n;
  }
  const auto& work = plan.tree.work;
  state.counters["s_per_step"] = benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["evaluations_per_step"] = static_cast<double>(work.evaluations - start.evaluations) / static_cast<double>(steps);
  state.counters["fallbacks"] = static_cast<double>(work.fallbacks - start.fallbacks);
}

void step_cost(benchmark::State& state, const std::string& source) { cycles(state, source, static_cast<double>(state.range(0))); }

// Depth state.range(0), 200 um.
void depth_cost(benchmark::State& state, const char* inner, bool nested, bool global_newton) {
  cycles(state, deep(static_cast<int>(state.range(0)), inner, nested), 200.0, global_newton);
}

}  // namespace

BENCHMARK_CAPTURE(step_cost, friction, std::string(kFriction))->Arg(50)->Arg(400);
BENCHMARK_CAPTURE(step_cost, bouc_wen, std::string(kBoucWen))->Arg(50)->Arg(400);
BENCHMARK_CAPTURE(step_cost, repro03_nested, repro("03_gap_bouc_wen_sundials"))->Arg(50)->Arg(400);
BENCHMARK_CAPTURE(step_cost, repro03_flat, std::string(kFlat03))->Arg(50)->Arg(400);
BENCHMARK_CAPTURE(step_cost, repro05_nested, repro("05_fixed_slow_gap_boucwen_inerter"))->Arg(50)->Arg(400);
BENCHMARK_CAPTURE(step_cost, repro05_flat, std::string(kFlat05))->Arg(50)->Arg(400);
BENCHMARK_CAPTURE(step_cost, repro06_nested, repro("06_fixed_slow_boucwen_yeoh_friction"))->Arg(50)->Arg(400);
BENCHMARK_CAPTURE(step_cost, repro06_flat, std::string(kFlat06))->Arg(50)->Arg(400);
BENCHMARK_CAPTURE(step_cost, repro07_nested, repro("07_fixed_harmonic_noconv_boucwen_maxwell"))->Arg(50)->Arg(400);
BENCHMARK_CAPTURE(step_cost, repro07_flat, std::string(kFlat07))->Arg(50)->Arg(400);
BENCHMARK_CAPTURE(step_cost, repro10_nested, repro("10_deep8_fixed_slow"))->Arg(50)->Arg(400);
BENCHMARK_CAPTURE(step_cost, repro10_flat, std::string(kFlat10))->Arg(50)->Arg(400);
BENCHMARK_CAPTURE(step_cost, repro11_nested, repro("11_fixed_slow_saturated_boucwen_chains"))->Arg(50)->Arg(400);
BENCHMARK_CAPTURE(step_cost, repro11_flat, std::string(kFlat11))->Arg(50)->Arg(400);
BENCHMARK_CAPTURE(step_cost, repro12_nested, repro("12_fixed_slow_saturated_boucwen_three_levels"))->Arg(50)->Arg(400);
BENCHMARK_CAPTURE(step_cost, repro12_flat, std::string(kFlat12))->Arg(50)->Arg(400);
BENCHMARK_CAPTURE(depth_cost, bouc_wen_nested, kInnerBoucWen, true, true)->DenseRange(2, 8);
BENCHMARK_CAPTURE(depth_cost, bouc_wen_flat, kInnerBoucWen, false, true)->DenseRange(2, 8);
BENCHMARK_CAPTURE(depth_cost, spring_nested, kInnerSpring, true, true)->DenseRange(2, 8);
BENCHMARK_CAPTURE(depth_cost, spring_nested_solve, kInnerSpring, true, false)->DenseRange(2, 8);
BENCHMARK_CAPTURE(depth_cost, spring_flat, kInnerSpring, false, true)->DenseRange(2, 8);
