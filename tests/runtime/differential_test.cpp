// Differential test of the two integrators (issue 26): seeded random valid networks
// (random_network.hpp: every element kind, blocks nested up to 6 deep) each run with the
// fixed-step kernels and with SUNDIALS IDA on a short history and two harmonic points (0.3 mm
// at 2 Hz, 0.05 mm at 20 Hz). Both must finish with finite forces and agree within the
// tolerances of docs/numerics.md ("Verification", differential row). The suite runs kModels
// models (fewer under AddressSanitizer, whose build CI also runs); tests/differential/run runs
// more (RHEO_DIFFERENTIAL_MODELS, RHEO_DIFFERENTIAL_SEED; RHEO_DIFFERENTIAL_VERBOSE=1 prints
// each model's CPU time by part; RHEO_DIFFERENTIAL_ONLY=i compares model i alone and prints its text;
// RHEO_DIFFERENTIAL_DEPTH sets the deepest nesting; RHEO_DIFFERENTIAL_DUMP=DIR writes each model
// with a simulate block to DIR/model_I.rheo and compares nothing, for tests/differential/cli_run).
//
// Where the time goes (100 models, seed 2026): IDA, in the history (restarted at each of its
// 100 samples) and in harmonic points; fixed steps take a few ms a model.
// A springpot is a chain of 22 Maxwell modes, 44 unknowns of IDA's dense Newton matrix (0.3-0.8 s
// a history), so a model holds at most one.
#include "random_network.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/dae/dae_graph.hpp"
#include "runtime/dae/dae_linear_start.hpp"
#include "runtime/dae/dae_protocols.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/protocols/solver_choice.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <numbers>

namespace differential_test {

using namespace rheo;

namespace {

// In the suite: 100 models take about 20 s of CPU in Release (docs/numerics.md). The sanitizer
// build (ASan + UBSan, RelWithDebInfo) runs a quarter of them, each several times slower.
constexpr int kModels = test::kUnderSanitizer ? 25 : 100;
constexpr std::uint64_t kSeed = 2026;  // RHEO_DIFFERENTIAL_SEED overrides
constexpr int kMaxDepth = 6;
constexpr int kRefine = 4;                // fixed steps per drive sample (the drive is the same piecewise-linear one), and twice that,
constexpr double kMassResolution = 0.25;  // or more, so that w dt <= this for the fastest internal mass (Newmark's period error (w dt)^2/12)
constexpr int kStepsPerCycle = 128;       // fixed steps per harmonic cycle, and twice that (IDA samples as many)
constexpr double kPeriodicity = 1e-4;     // the state's change over a cycle that ends a harmonic point
constexpr int kCycles = 24;               // per harmonic point: a point short of its periodic state is not compared
constexpr int kSettleBudget = 8;          // unless IDA's settles: then fixed steps get this many times the cycles, and must settle
// Agreement, docs/numerics.md: history forces to this fraction of the largest |F| (fixed steps
// are extrapolated, but sliders and gaps switch inside steps); harmonic stiffness relative and
// damping absolute, on points where both reached their periodic state.
constexpr double kHistoryTolerance = 2e-2;
constexpr double kStiffnessTolerance = 5e-3;
constexpr double kDampingTolerance = 5e-3;  // d = U/(pi F^ u0), absolute (0.3 deg in phase where it is small)

long environment(const char* name, long fallback) {
  const char* value = std::getenv(name);
  return value ? std::strtol(value, nullptr, 10) : fallback;
}

// 0.1 s at 1 kHz from rest: two tones, so that rates reverse at unrelated times.
runtime::Drive test_drive() {
  runtime::Drive d;
  for (int k = 0; k <= 100; ++k) {
    const double t = 1e-3 * k;
    d.time.push_back(t);
    d.displacement.push_back(0.3 * std::sin(2 * std::numbers::pi * 10 * t) + 0.05 * std::sin(2 * std::numbers::pi * 37 * t));
  }
  return d;
}

// The protocols of a dumped model, as the command line runs them (tests/differential/cli_run
// writes drive.csv beside it): a history and a 2 x 2 harmonic grid.
void dump_model(const std::string& directory, long index, const std::string& source) {
  const std::string path = fmt::format("{}/model_{:04d}.rheo", directory, index);
  std::ofstream file(path);
  file << source << "simulate {\n  history file = \"drive.csv\"\n  harmonic frequency = [2, 20] Hz, amplitude = [0.05, 0.4] mm\n}\n";
  REQUIRE_MESSAGE(file.good(), "cannot write " << path);
}

// The same piecewise-linear drive with `r` samples per interval.
runtime::Drive refined(const runtime::Drive& d, int r) {
  runtime::Drive out{{d.time.front()}, {d.displacement.front()}};
  for (std::size_t k = 1; k < d.time.size(); ++k)
    for (int j = 1; j <= r; ++j) {
      out.time.push_back(d.time[k - 1] + (d.time[k] - d.time[k - 1]) * j / r);
      out.displacement.push_back(d.displacement[k - 1] + (d.displacement[k] - d.displacement[k - 1]) * j / r);
    }
  return out;
}

struct Worst {
  double history = 0.0, stiffness = 0.0, damping = 0.0;
  int harmonic_compared = 0, harmonic_points = 0;
  int refined_histories = 0, refined_points = 0;  // compared again at finer fixed steps
  int fixed_settled_late = 0;                     // fixed-step points run again with kSettleBudget times the cycles
  std::string timing;                             // of the last model: CPU seconds of each part, and each harmonic point's cycles (! not periodic)
};

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

std::string cycles(const runtime::HarmonicPoint& p) { return fmt::format("{}{}", p.cycles, p.converged ? "" : "!"); }

// FASTEST_MASS: the largest natural frequency of an internal mass [rad/s] (0: none).
void compare(const std::string& source, double fastest_mass, Worst& worst) {
  worst.timing = "history: IDA failed";  // until the history is done
  const double started = cpu_seconds();
  const runtime::Network network = test::network_from(source, "m");
  const runtime::Drive drive = test_drive();
  // The drive's kinks excite internal masses at their natural frequency, which fixed steps must
  // resolve for the extrapolation to hold.
  const double sample = drive.time[1] - drive.time[0];
  const int refine = std::max(kRefine, static_cast<int>(std::ceil(fastest_mass * sample / kMassResolution)));
  const runtime::History ida = runtime::run_history(network, drive, false, runtime::SolverChoice::sundials);
  const double ida_done = cpu_seconds();
  // Fixed steps are first order where nested dashpots are: extrapolated from r and 2r steps per
  // sample (Richardson), 2 F(2r) - F(r). Where a slider or gap switches inside steps the error is
  // not yet smooth in the step at r = 4 (seed 2026, model 50: 3.1e-2 of max |F| extrapolated from
  // 4 and 8, 4.6e-5 from 64 steps per sample alone): a model outside the tolerance is compared
  // again at 4, then 16 times the steps (counted in Worst::refined_histories), and judged on the first
  // comparison within the tolerance, or the last.
  double history = 0.0;
  for (int more = 1; more <= 16; more *= 4) {
    const int r = refine * more;
    const runtime::History coarse = runtime::run_history(network, refined(drive, r), false, runtime::SolverChoice::fixed);
    const runtime::History fine = runtime::run_history(network, refined(drive, 2 * r), false, runtime::SolverChoice::fixed);
    worst.timing = fmt::format("history: IDA {:.2f} s, fixed {:.2f} s ({} steps per sample)", ida_done - started, cpu_seconds() - ida_done, r);
    double scale = 0.0, difference = 0.0;
    for (std::size_t k = 0; k < drive.time.size(); ++k) {
      const double a = ida.force[k], b = 2.0 * fine.force[2 * k * static_cast<std::size_t>(r)] - coarse.force[k * static_cast<std::size_t>(r)];
      REQUIRE(std::isfinite(a));
      REQUIRE(std::isfinite(b));
      scale = std::max(scale, std::abs(a));
      difference = std::max(difference, std::abs(a - b));
    }
    history = difference / std::max(scale, 1e-9);
    if (history <= kHistoryTolerance) break;
    if (more == 1) ++worst.refined_histories;
  }
  CHECK_MESSAGE(history <= kHistoryTolerance, "history forces differ by ", history, " of max |F|");
  worst.history = std::max(worst.history, history);

  // A springpot's chain has a slow tail mode of l_hi (1 + alpha)/alpha >= 5 s (f_low = 1 Hz,
  // springpot.hpp). IDA's harmonic point starts at the periodic state of the linearised network
  // (dae_linear_start.hpp) and settles at once; where the network has a gap, a quadratic dashpot
  // or a bouc_wen it starts from rest, and the geometric skip (geometric_settling.hpp) settles the
  // tail in tens of cycles, but each costs IDA 1-2 s with the chain's 44 unknowns: those points are
  // left out here (with them, seed 2026: 171 of 200 points compared, all within the tolerances,
  // in 97 s instead of 15 s). Fixed steps still run them; the history compares the chain on both.
  const bool ida_harmonic = source.find("springpot") == std::string::npos ||
                            runtime::dae_linear_periodic_start(runtime::DaeGraph::build(network), 1.0, 1.0).has_value();
  runtime::HarmonicOptions options;
  options.steady_state = runtime::SteadyState::time_stepping;
  options.max_cycles = kCycles;
  options.tolerance = kPeriodicity;
  for (const auto& level : {std::pair{0.3, 2.0}, std::pair{0.05, 20.0}}) {
    const double amplitude = level.first, frequency = level.second;  // not a structured binding: Clang 14 cannot capture one
    CAPTURE(amplitude);
    CAPTURE(frequency);
    // IDA's point sampled as finely as the finer fixed-step run: K and d are formed from the
    // samples, and where a gap or slider switches between two of them the energy's quadrature
    // is first order (seed 31337, model 238: d 0.5396 from 256 samples a cycle, 0.5461 from
    // 2048, fixed steps 0.5465 at 65536).
    const auto ida_point = [&](int samples_per_cycle) {
      options.steps_per_cycle = samples_per_cycle;
      options.solver = runtime::SolverChoice::sundials;
      runtime::HarmonicPoint p = runtime::simulate_harmonic_point(network, amplitude, frequency, options);
      options.solver = runtime::SolverChoice::fixed;
      return p;
    };
    const double before = cpu_seconds();
    runtime::HarmonicPoint a = ida_harmonic ? ida_point(2 * kStepsPerCycle) : runtime::HarmonicPoint{};
    const double between = cpu_seconds();
    // Extrapolated from N and 2N fixed steps per cycle; outside the tolerances (a gap or slider
    // switching inside steps, as for the history) compared again at 4N and 16N, IDA's samples
    // refined alike, and judged on the first comparison within them, or the last.
    // Where IDA reached its periodic state, fixed steps must reach theirs too: a point that still
    // moves after kSettleBudget times the cycles is a fault of the fixed-step path (a drift that
    // its skip to the periodic state amplified went unnoticed here while such points were left
    // out), reported and counted.
    const auto fixed_point = [&](int steps_per_cycle) {
      options.steps_per_cycle = steps_per_cycle;
      runtime::HarmonicPoint p = runtime::simulate_harmonic_point(network, amplitude, frequency, options);
      if (p.converged || !ida_harmonic || !a.converged) return p;
      ++worst.fixed_settled_late;
      options.max_cycles = kSettleBudget * kCycles;
      p = runtime::simulate_harmonic_point(network, amplitude, frequency, options);
      CHECK_MESSAGE(p.converged, "fixed steps (", steps_per_cycle, " a cycle) do not settle in ", options.max_cycles,
                    " cycles where IDA settles in ", a.cycles);
      options.max_cycles = kCycles;
      return p;
    };
    double stiffness = 0.0, damping = 0.0;
    bool compared = false;
    for (int more = 1; more <= 16; more *= 4) {
      if (more > 1 && ida_harmonic && a.converged) a = ida_point(2 * kStepsPerCycle * more);
      const runtime::HarmonicPoint b_fine = fixed_point(2 * kStepsPerCycle * more);
      const runtime::HarmonicPoint b_coarse = fixed_point(kStepsPerCycle * more);
      if (more == 1)
        worst.timing += fmt::format("; {} Hz: IDA {:.2f} s ({} cycles), fixed {:.2f} s ({} and {} cycles)", frequency, between - before, cycles(a),
                                    cpu_seconds() - between, cycles(b_fine), cycles(b_coarse));
      for (const runtime::HarmonicPoint* p : {static_cast<const runtime::HarmonicPoint*>(&a), &b_fine, &b_coarse})
        REQUIRE(std::isfinite(p->measures.stiffness));
      if (!ida_harmonic || !a.converged || !b_fine.converged || !b_coarse.converged) break;
      // A point inside a gap's play carries no force on either side: it has no phase to compare.
      // IDA's may be a transient's rounding residue instead of 0 (seed 17, model 108: 9e-223 N
      // where a quadratic dashpot has pushed the gap clear), or what its tolerances leave: a
      // position's tolerance, rtol times the length scale, through a spring in series with the
      // open gap (seed 59, model 189: 3.3e-9 N, 6e-10 of the scale, where fixed steps give 0), or
      // through the stiff springs in series with a gap that a dashpot beside them has pushed to
      // touch at the end of the stroke (seed 71, model 169: 6.8e-6 N on IDA and 1.1e-5 N on fixed
      // steps in 24 cycles, 1.8e-9 N when fixed steps settle further, behind 58375 and 8345 N/mm;
      // the point's force tends to 0). Below 100 times IDA's rtol of what the network carries at
      // this amplitude and rate, or 10 times what a position's tolerance carries through the
      // stiffest spring (a weighted norm over the unknowns), counts as none.
      const double no_force = runtime::kDaeRelativeTolerance *
                              std::max(100.0 * runtime::dae_force_scale(network, amplitude, 2.0 * std::numbers::pi * frequency * amplitude),
                                       10.0 * runtime::stiffest_spring_force(runtime::DaeGraph::build(network), amplitude));
      if (a.measures.force_amplitude <= no_force && b_fine.measures.force_amplitude <= no_force && b_coarse.measures.force_amplitude <= no_force)
        break;
      compared = true;
      const double b_stiffness = 2.0 * b_fine.measures.stiffness - b_coarse.measures.stiffness;
      const double b_damping = 2.0 * b_fine.measures.damping - b_coarse.measures.damping;
      stiffness = test::relative_error(b_stiffness, a.measures.stiffness);
      // The damping d = sin(phase), not the phase: near 90 deg asin turns 1e-4 in d into 0.8 deg.
      damping = std::abs(b_damping - a.measures.damping);
      if (stiffness <= kStiffnessTolerance && damping <= kDampingTolerance) break;
      if (more == 1) ++worst.refined_points;
    }
    if (!ida_harmonic) continue;
    ++worst.harmonic_points;
    if (!compared) continue;
    ++worst.harmonic_compared;
    CHECK(stiffness <= kStiffnessTolerance);
    CHECK(damping <= kDampingTolerance);
    worst.stiffness = std::max(worst.stiffness, stiffness);
    worst.damping = std::max(worst.damping, damping);
  }
}

// Whether IDA refuses the model (DaeGraph::build's rules); check then names the rule.
bool refuses(const std::string& source) {
  try {
    (void)runtime::DaeGraph::build(test::network_from(source, "m"));
    return false;
  } catch (const runtime::ModelError& error) {
    CHECK(std::string(error.what()).find("merge the sliders") != std::string::npos);
    return true;
  }
}

// After a NumericalError (MESSAGE) on SOURCE: true where `solver = auto` takes fixed steps and its
// default history and harmonic points run with finite forces; a failed check otherwise.
bool fixed_by_default(const std::string& source, const std::string& message) {
  const runtime::Network network = test::network_from(source, "m");
  if (runtime::uses_sundials(network, runtime::SolverChoice::automatic)) {
    FAIL_CHECK(message);
    return false;
  }
  MESSAGE("IDA: ", message, " (auto takes fixed steps)");
  for (double force : runtime::run_history(network, test_drive(), false).force) REQUIRE(std::isfinite(force));
  runtime::HarmonicOptions options;
  for (const auto& [amplitude, frequency] : {std::pair{0.3, 2.0}, std::pair{0.05, 20.0}})
    REQUIRE(std::isfinite(runtime::simulate_harmonic_point(network, amplitude, frequency, options).measures.stiffness));
  return true;
}

}  // namespace

TEST_CASE("differential: random networks to depth 6 agree between fixed steps and IDA") {
  const long models = environment("RHEO_DIFFERENTIAL_MODELS", kModels);
  const long only = environment("RHEO_DIFFERENTIAL_ONLY", -1);  // the models before it are still drawn
  const auto seed = static_cast<std::uint64_t>(environment("RHEO_DIFFERENTIAL_SEED", static_cast<long>(kSeed)));
  const int depth = static_cast<int>(environment("RHEO_DIFFERENTIAL_DEPTH", kMaxDepth));
  test::RandomNetwork generator(seed, depth);
  const char* dump_directory = std::getenv("RHEO_DIFFERENTIAL_DUMP");
  const char* verbose_setting = std::getenv("RHEO_DIFFERENTIAL_VERBOSE");
  const bool verbose = verbose_setting && *verbose_setting;
  Worst worst;
  const auto start = std::chrono::steady_clock::now();
  long refused = 0, ida_failed_where_auto_is_fixed = 0;
  for (long i = 0; i < models; ++i) {
    std::string source = generator.model("m");
    // The generator's rules avoid most networks IDA refuses; a slider or gap that meets another
    // at a node nothing else holds (through friction elements and parallel blocks), or sliders
    // in parallel, are drawn again.
    while (refuses(source)) {
      ++refused;
      source = generator.model("m");
    }
    if (only >= 0 && i != only) continue;
    if (only >= 0) MESSAGE(source);
    if (dump_directory) {
      dump_model(dump_directory, i, source);
      continue;
    }
    CAPTURE(i);
    CAPTURE(source);  // a failure prints the model: save it as a reproducer
    const auto before = std::chrono::steady_clock::now();
    try {
      compare(source, generator.fastest_mass(), worst);
    } catch (const NumericalError& error) {  // from either integrator: the next model still runs
      // Where `solver = auto` takes fixed steps (a bouc_wen inside a series block,
      // solver_choice.hpp), an IDA failure is counted and reported (seed 37, model 85 failed
      // with IDA_CONV_FAIL until the Bouc-Wen branch became an event, dae_bouc_wen.cpp; no
      // model of seeds 37, 41, 53, 59, 61, 67 and 71 fails on IDA now), and the default run must then succeed
      // with finite forces; the comparison covers the model only as far as IDA got.
      if (fixed_by_default(source, error.what())) ++ida_failed_where_auto_is_fixed;
    } catch (const std::exception& error) {
      FAIL_CHECK(std::string(error.what()));
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count();
    if (verbose) MESSAGE("model ", i, ": ", seconds, " s; CPU ", worst.timing);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  MESSAGE(models, " models (seed ", seed, ") in ", seconds, " s; worst: history ", worst.history, " of max |F|, stiffness ", worst.stiffness,
          ", damping ", worst.damping, "; ", worst.refined_histories, " histories and ", worst.refined_points, " harmonic points refined; ",
          worst.fixed_settled_late, " fixed-step points settled late; harmonic points compared ", worst.harmonic_compared, " of ",
          worst.harmonic_points, "; ", refused, " models drawn again; IDA failed on ", ida_failed_where_auto_is_fixed,
          " models that auto runs on fixed steps");
  // Few models are drawn again, and a fair share of points reach their periodic state within
  // the cycle budget: the comparison is not vacuous (for a whole run, not one model).
  if (only >= 0 || dump_directory) return;
  CHECK(refused * 5 <= models);
  CHECK(worst.harmonic_compared * 4 >= worst.harmonic_points);
}

TEST_CASE("differential: the generator is deterministic and covers every element kind") {
  test::RandomNetwork a(7, kMaxDepth), b(7, kMaxDepth);
  std::string text;
  for (int i = 0; i < 60; ++i) {
    const std::string model = a.model("m");
    CHECK(model == b.model("m"));
    text += model;
  }
  for (const char* kind : {"spring (", "yeoh (", "poly_spring (", "dashpot (", "quadratic_dashpot (", "maxwell (", "friction (", "slider (",
                           "gap (", "inerter (", "springpot (", "bouc_wen (", "series {", "parallel {"}) {
    CAPTURE(kind);
    CHECK(text.find(kind) != std::string::npos);
  }
}

}  // namespace differential_test
