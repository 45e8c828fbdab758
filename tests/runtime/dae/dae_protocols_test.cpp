// Protocols on the variable-step backend: the hydrobushing of examples/data on IDA against the
// exact event-driven periodic state and against the file (accurate to about 0.06 % and 0.03 deg,
// examples/data/README.md), and the fixed-step and SUNDIALS backends agreeing on every smooth
// standard-library model.
#include "lang/stdlib.hpp"
#include "runtime/protocols/run_history.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/dae/dae_protocols.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/io/harmonic_data.hpp"
#include "support.hpp"
#include "two_tone_reference.hpp"

#include <doctest/doctest.h>

#include <complex>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <vector>

namespace dae_protocols_test {

using namespace rheo;

TEST_CASE("examples/hydrobushing.rheo on IDA: the event-driven periodic state, and the reference file to its accuracy") {
  const auto network = test::network_from(test::read_file(RHEO_EXAMPLES_DIR "/hydrobushing.rheo"), "hydrobushing");
  CHECK(runtime::uses_sundials(network, runtime::SolverChoice::automatic));
  const auto data = runtime::read_harmonic_data(RHEO_DATA_DIR "/hydrobushing_reference.csv");
  runtime::HarmonicOptions ida, events;
  ida.solver = runtime::SolverChoice::sundials;  // auto would take the event-driven periodic state
  ida.steps_per_cycle = 256;
  ida.threads = 2;
  events.steady_state = runtime::SteadyState::closed_form;
  const auto points = runtime::simulate_harmonic_grid(
      network, {0.1, 0.2, 0.5, 0.8, 1.0, 1.5, 2.0},
      [] {
        std::vector<double> f;
        for (double v = 1.0; v <= 41.0; v += 2.0) f.push_back(v);
        return f;
      }(),
      ida);
  REQUIRE(points.size() == data.size());
  double worst_stiffness = 0.0, worst_phase = 0.0, file_stiffness = 0.0, file_phase = 0.0;
  for (std::size_t i = 0; i < data.size(); ++i) {
    const auto& p = points[i];
    CAPTURE(p.amplitude);
    CAPTURE(p.frequency);
    REQUIRE(p.amplitude == data.amplitude[i]);
    REQUIRE(p.frequency == data.frequency[i]);
    REQUIRE(p.converged);
    REQUIRE(p.cycles > 0);  // simulated, not the closed form
    const auto exact = runtime::simulate_harmonic_point(network, p.amplitude, p.frequency, events);
    worst_stiffness = std::max(worst_stiffness, test::relative_error(p.measures.stiffness, exact.measures.stiffness));
    worst_phase = std::max(worst_phase, std::abs(test::degrees(p.measures.phase - exact.measures.phase)));
    file_stiffness = std::max(file_stiffness, test::relative_error(p.measures.stiffness, data.stiffness[i]));
    file_phase = std::max(file_phase, std::abs(test::degrees(p.measures.phase - data.phase[i])));
  }
  MESSAGE("hydrobushing on IDA: worst stiffness error " << worst_stiffness << ", worst phase error " << worst_phase
                                                        << " deg against the event-driven periodic state; " << file_stiffness << " and "
                                                        << file_phase << " deg against the file");
  // IDA (rtol 1e-8) is far finer than its N = 256 samples per cycle: F^ is the largest sample
  // and U the trapezoidal loop integral, both second order, off by up to (pi/N)^2 = 1.5e-4
  // relative (a sampled sinusoid's peak: (pi/N)^2 / 2), so d = U/(pi F^ u0) by about as much
  // (8.6e-3 deg as a phase). Observed 1.0e-4 and 2.5e-3 deg.
  const double sampling = std::pow(std::numbers::pi / 256.0, 2);
  CHECK(worst_stiffness < sampling);
  CHECK(worst_phase < test::degrees(sampling));
  // The file: about 0.06 % and 0.03 deg (examples/data/README.md), plus the sampling.
  CHECK(file_stiffness < 6e-4 + sampling);
  CHECK(file_phase < 0.03 + test::degrees(sampling));
}

TEST_CASE("fixed-step and SUNDIALS agree on every standard-library model") {
  // Fixed steps are exact for root-parallel networks (closed form), second order in an inerter
  // and first order in a dashpot behind an internal node (hydromount's channel), so the fixed-step
  // values are Richardson-extrapolated from 4096 and 8192 steps per cycle (2 K(2N) - K(N)),
  // which leaves the exact ones unchanged; both paths then agree to the IDA tolerance.
  for (const auto& name : lang::stdlib_names()) {
    // Its springpot chain's slowest elements (relaxation times of hours) settle only after
    // thousands of cycles from rest; springpot_test cross-checks it (closed form, histories).
    if (name == "fractional_zener") continue;
    const auto network = test::network_from("import " + name + "\nmodel m { " + name + " x () }", "m");
    for (double u0 : {0.03, 0.4}) {
      for (double f : {1.0, 15.0}) {
        runtime::HarmonicOptions fixed;
        fixed.solver = runtime::SolverChoice::fixed;
        fixed.steady_state = runtime::SteadyState::time_stepping;
        fixed.steps_per_cycle = 4096;
        const auto coarse = runtime::simulate_harmonic_point(network, u0, f, fixed);
        fixed.steps_per_cycle = 8192;
        const auto fine = runtime::simulate_harmonic_point(network, u0, f, fixed);
        const double stiffness = 2.0 * fine.measures.stiffness - coarse.measures.stiffness;
        const double phase = 2.0 * fine.measures.phase - coarse.measures.phase;
        runtime::HarmonicOptions sundials;
        sundials.solver = runtime::SolverChoice::sundials;
        sundials.steps_per_cycle = 1024;
        const auto b = runtime::simulate_harmonic_point(network, u0, f, sundials);
        CAPTURE(name);
        CAPTURE(u0);
        CAPTURE(f);
        CHECK(fine.converged);
        CHECK(b.converged);
        CHECK(test::relative_error(b.measures.stiffness, stiffness) < 2e-5);
        CHECK(std::abs(test::degrees(b.measures.phase - phase)) < 2e-3);
      }
    }
  }
}

TEST_CASE("fixed-step and SUNDIALS agree on a quasi-static history of a frictional network") {
  const auto network = test::network_from(
      "import series_friction_maxwell\nmodel m { series_friction_maxwell s ()\n friction f (k = 300 N/mm, uy = 0.05 mm) }", "m");
  const auto drive = runtime::quasistatic_sine({1.0, 0.3}, 2.0, 2, 2000);
  const auto fixed = runtime::run_history(network, drive, false, runtime::SolverChoice::fixed);
  const auto dae = runtime::run_history(network, drive, false, runtime::SolverChoice::sundials);
  double scale = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < drive.time.size(); ++i) {
    scale = std::max(scale, std::abs(fixed.force[i]));
    worst = std::max(worst, std::abs(fixed.force[i] - dae.force[i]));
  }
  MESSAGE("history: worst force difference " << worst << " N of " << scale << " N");
  CHECK(worst < 1e-4 * scale);
}

TEST_CASE("IDA failing on a yeoh that softens in series names the yeoh and its limit, below the limit it agrees with fixed steps") {
  const auto network = test::network_from("model y { series { yeoh r (D10 = 1, D20 = -1, D30 = 0) spring k (k = 1) } }", "y");
  runtime::HarmonicOptions options;
  options.solver = runtime::SolverChoice::sundials;
  CHECK_THROWS_WITH_AS(runtime::dae_harmonic_point(network, 2.0, 1.0, options),
                       doctest::Contains("Likely cause: yeoh 'r' softens to zero tangent stiffness at |e| = 0.408248 mm"), runtime::NumericalError);
  const auto dae = runtime::dae_harmonic_point(network, 0.5, 1.0, options);
  options.solver = runtime::SolverChoice::fixed;
  const auto fixed = runtime::simulate_harmonic_point(network, 0.5, 1.0, options);
  CHECK(dae.measures.stiffness == doctest::Approx(fixed.measures.stiffness).epsilon(1e-5).scale(0.0));
}

// Reproducer 09 of tests/corpus/repro/backends (issue 26): an undamped mass behind a slider. At
// 2 Hz the slider sticks and the mass swings on its spring; IDA starts from rest, the free
// oscillation never decays, and a periodic state that is unique does not exist. The point ends
// unconverged and `stalled` (its change over a cycle does not halve); a Maxwell arm settling
// geometrically (e^(-T/tau) = 0.61 a cycle) but short of its cycles is not stalled.
TEST_CASE("IDA harmonic point: an undamped free oscillation is stalled, a slow geometric settling is not") {
  runtime::HarmonicOptions options;
  options.solver = runtime::SolverChoice::sundials;
  options.steps_per_cycle = 64;
  options.max_cycles = 40;
  // Reproducer 09 from rest: the slider stays stuck, and the free oscillation of the mass on its
  // spring that the start excites is never damped. (A gap that never closes keeps the point from
  // the linear periodic start, which settles reproducer 09 at once: dae_linear_start_test.)
  const auto undamped = test::network_from(
      "model m { maxwell (k = 123.874 N/mm, tau = 20.4112 ms)\n series { slider (fy = 1.67762 N)\n"
      " series { spring (k = 115086 N/m)\n inerter (b = 11.7486 kg) } }\n series { gap (width = 10 mm)\n spring (k = 1 N/mm) } }",
      "m");
  const auto swinging = runtime::simulate_harmonic_point(undamped, 0.4, 2.0, options);
  CHECK_FALSE(swinging.converged);
  CHECK(swinging.stalled);
  CHECK(swinging.residual > 1e-2);
  // A gap that never closes keeps the point from the linear start (dae_linear_start.hpp), so the
  // Maxwell element settles from rest, by a factor exp(-T/tau) = 0.61 a cycle.
  const auto slow = test::network_from(
      "model m { spring (k = 10 N/mm)\n maxwell (k = 100 N/mm, tau = 100 ms)\n"
      " series { gap (width = 10 mm)\n spring (k = 1 N/mm) } }",
      "m");
  // Four cycles are too few for the geometric skip (it needs three changes and a cycle after).
  options.max_cycles = 4;
  const auto settling = runtime::simulate_harmonic_point(slow, 0.4, 20.0, options);
  CHECK_FALSE(settling.converged);
  CHECK_FALSE(settling.stalled);
  options.max_cycles = 200;
  const auto settled = runtime::simulate_harmonic_point(slow, 0.4, 20.0, options);
  CHECK(settled.converged);
  CHECK_FALSE(settled.stalled);
  // The geometric skip (geometric_settling.hpp) settles it in 6 cycles (23 without), at the
  // closed form |K*| = |k + k_m i w tau / (1 + i w tau)| up to the extremes of 64 samples a cycle
  // (low by at most 1 - cos(pi/64) = 1.2e-3; observed 3.4e-4).
  CHECK(settled.cycles <= 10);
  const std::complex<double> iwt(0.0, 2.0 * std::numbers::pi * 20.0 * 0.1);
  const double closed_form = std::abs(10.0 + 100.0 * iwt / (1.0 + iwt));
  CHECK(settled.measures.stiffness <= closed_form * (1.0 + 1e-9));
  CHECK(settled.measures.stiffness >= closed_form * (1.0 - 1.2e-3));
}

// Differential seed 73, model 243: a slider yielding at 0.64 N in tension and 7.6 N in
// compression, in series with a springpot (no static stiffness) and nonlinear springs. At 0.05
// mm / 20 Hz it slips only in tension and ratchets: its positions move on by about 0.04 mm every
// cycle. Those changes' rates (0.9995) passed as a slow contraction, the geometric skip moved the
// positions by 83 mm, and IDA found no consistent state there (IDACalcIC, exit 5). The skip is
// undone and its components are not moved again: the point runs its cycles and is reported as not
// converged, its skip refused, with finite measures.
constexpr int kSamples = 256;  // a cycle
constexpr int kCycles = 24;    // the skip comes after 16

TEST_CASE("IDA harmonic point: a ratchet's drift is not skipped to where IDA finds no state (differential seed 73, model 243)") {
  const auto network = test::network_from(
      "model m { series {\n"
      " springpot (k = 206.225 N/mm, alpha = 0.879664, tau = 2.75324 ms, f_low = 1 Hz, f_high = 100 Hz)\n"
      " parallel { maxwell (k = 1294.07 N/mm, tau = 16.6889 ms)\n"
      "  series { poly_spring (k1 = 12.0284 N/mm, k2 = 3.44644 N/mm^2, k3 = 17.0796 N/mm^3)\n"
      "   parallel { yeoh (D10 = 438.194 N/mm, D20 = 0 N/mm^3, D30 = 0 N/mm^5)\n"
      "    maxwell (k = 1605.99 N/mm, tau = 1.0062 ms)\n"
      "    poly_spring (k1 = 1271.29 N/mm, k2 = -2273.61 N/mm^2, k3 = 1673.52 N/mm^3) } } }\n"
      " slider (fy_pos = 0.640767 N, fy_neg = 7.63665 N)\n"
      " poly_spring (k1 = 134.613 N/mm, k2 = 0 N/mm^2, k3 = 0 N/mm^3) } }",
      "m");
  runtime::HarmonicOptions options;
  options.solver = runtime::SolverChoice::sundials;
  options.steady_state = runtime::SteadyState::time_stepping;
  options.steps_per_cycle = kSamples;
  options.tolerance = 1e-6;
  options.max_cycles = kCycles;
  runtime::HarmonicPoint point;
  REQUIRE_NOTHROW(point = runtime::simulate_harmonic_point(network, 0.05, 20.0, options));
  CHECK_FALSE(point.converged);
  CHECK(point.skip_refused);
  CHECK(point.cycles == kCycles);
  CHECK(std::isfinite(point.measures.stiffness));
  CHECK(point.measures.stiffness > 0.0);
  CHECK(std::isfinite(point.measures.phase));
}

// IDA's point of NETWORK at AMPLITUDE [mm] and FREQUENCY [Hz], SAMPLES a cycle, settled to a
// change of 1e-6 in at most MOST cycles (of 400 allowed), and within 1e-4 of extrapolated fixed
// steps in K (relative) and d (absolute).
void check_settles_on_ida(const runtime::Network& network, double amplitude, double frequency, int samples, int most) {
  runtime::HarmonicOptions options;
  options.steady_state = runtime::SteadyState::time_stepping;
  options.tolerance = 1e-6;
  options.max_cycles = 400;
  options.solver = runtime::SolverChoice::sundials;
  options.steps_per_cycle = samples;
  const auto ida = runtime::simulate_harmonic_point(network, amplitude, frequency, options);
  MESSAGE("cycles ", ida.cycles);
  REQUIRE(ida.converged);
  CHECK(ida.cycles <= most);
  const test::HarmonicGap gap = test::gap_to_extrapolated_fixed_point(network, ida, options);
  MESSAGE("K ", gap.stiffness, ", d ", gap.damping);
  CHECK(gap.stiffness < 1e-4);
  CHECK(gap.damping < 1e-4);
}

// A springpot behind a gap: IDA's point starts from rest (no linear start with a gap), and the
// chain's slow tail (l_hi (1 + alpha)/alpha, seconds) settled by 1e-4 a cycle: 400 cycles and
// 22 s without reaching a change of 1e-6. The component-wise geometric skip settles it in under
// 30 cycles, at fixed steps' answer (2048 and 4096 steps a cycle, extrapolated; observed 2.4e-5
// in K, 4e-5 in d at IDA's 256 samples a cycle).
TEST_CASE("IDA harmonic point: a springpot behind a gap settles by the geometric skip, at extrapolated fixed steps") {
  const auto network = test::network_from(
      "model m { spring (k = 100 N/mm)\n series { gap (width = 0.1 mm)\n"
      " springpot (k = 100 N/mm, alpha = 0.5, tau = 10 ms, f_low = 1 Hz, f_high = 100 Hz) } }",
      "m");
  for (const double frequency : {2.0, 20.0}) {
    CAPTURE(frequency);
    check_settles_on_ida(network, 0.3, frequency, 256, 30);
  }
}

// Differential seed 2026, model 0: a springpot beside a dashpot, a gap and a Maxwell element (and
// a spring and an inerter-damper pair). IDA's point at 20 Hz, 0.05 mm settled by a contact mode
// at 0.994 a cycle whose changes fell below the skip's floor while it lay 1e-5 from its limit:
// 313 cycles at 2048 samples a cycle; with the skip judged by the distance left, 64.
TEST_CASE("IDA harmonic point: a slow contact mode below the change floor is skipped by its distance left (differential seed 2026, model 0)") {
  const auto network = test::network_from(
      "model m {\n series {\n  springpot (k = 5.8456 N/mm, alpha = 0.65348, tau = 3.81624 ms, f_low = 1 Hz, f_high = 100 Hz)\n"
      "  series { spring (k = 14.422 N/mm) parallel { inerter (b = 0.152769 kg) dashpot (c = 0.271861 N*s/mm) } }\n }\n"
      " series {\n  dashpot (c = 0.0110533 N*s/mm)\n  gap (width = 0.0223838 mm, center = -0.000276622 mm)\n"
      "  maxwell (k = 8.45842 N/mm, c = 0.0454045 N*s/mm)\n }\n}",
      "m");
  check_settles_on_ida(network, 0.05, 20.0, 2048, 100);  // the default samples (at 256 the old skip settled in 48 cycles)
}

}  // namespace dae_protocols_test
