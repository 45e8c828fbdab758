#include "runtime/protocols/harmonic.hpp"

#include "runtime/dae/dae_protocols.hpp"
#include "runtime/core/parallel_for.hpp"
#include "runtime/closed_form/periodic_closed_form.hpp"
#include "runtime/stepping/periodic_start.hpp"
#include "runtime/stepping/relaxed_state.hpp"
#include "runtime/stepping/simulator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace rheo::runtime {
namespace {

// Scales of the state variables of a cycle: forces by F^ [N], elongations by u0 [mm],
// velocities by w u0 [mm/s], times by the period [s].
struct CycleScales {
  double force, length, velocity, time;
  double of(StateScale kind) const {
    switch (kind) {
      case StateScale::force: return force;
      case StateScale::length: return length;
      case StateScale::velocity: return velocity;
      case StateScale::time: return time;
    }
    return force;
  }
};

// Largest change of any state variable over a cycle, relative to its scale.
double cycle_change(const Topology& t, const std::vector<double>& start, const std::vector<double>& end, const CycleScales& scales) {
  double change = 0.0;
  for (std::size_t i = 0; i < start.size(); ++i) change = std::max(change, std::abs(end[i] - start[i]) / scales.of(t.state_scales[i]));
  return change;
}

// Whether the cycle-to-cycle change contracts at a steady geometric rate: the last two rates
// lie in [0.3, 1 - 1e-7] (faster, a few cycles finish anyway) and agree within 5 % of rho up
// to 0.999, within 5 % of 1 - rho beyond. The skip multiplies the last change by rho/(1 - rho)
// (up to 1e7), so an error d rho in rho errs by d rho/(1 - rho) of the remaining distance: at
// most 5 % of it, which the next skips remove (a gap's play shared with a bouc_wen's set,
// rho = 0.9993: tests/corpus/repro/backends/03).
bool steady_contraction(double rate, double previous_rate) {
  const double spread = std::abs(rate - previous_rate);
  if (rate >= 0.3 && rate <= 0.999) return spread <= 0.05 * rate;
  return rate > 0.999 && rate <= 1.0 - 1e-7 && spread <= 0.05 * (1.0 - rate);
}

// A slow mode (a Maxwell element with tau >> period in a subtree that starts at rest) moves the
// end-of-cycle state by d_n = s_n - s_{n-1} with d_{n+1} = rho d_n, so the periodic state is
// s_n + d_n rho / (1 - rho): jump there. The skip is only a better start; convergence is still
// declared on the change over simulated cycles, and a poor skip costs cycles, not accuracy.
void skip_geometric_tail(const std::vector<double>& cycle_start, double rho, std::vector<double>& state) {
  const double factor = rho / (1.0 - rho);
  for (std::size_t i = 0; i < state.size(); ++i) state[i] += factor * (state[i] - cycle_start[i]);
}

}  // namespace

namespace {
HarmonicPoint steady_point(const Network& network, double amplitude, double frequency, const HarmonicOptions& options, double preload);
}  // namespace

bool uses_closed_form(const Network& network, const HarmonicOptions& options) {
  if (options.steady_state == SteadyState::time_stepping || options.solver == SolverChoice::sundials) return false;
  const bool events = options.solver == SolverChoice::automatic || options.steady_state == SteadyState::closed_form;
  return has_closed_form_periodic_state(network, events);
}

HarmonicPoint simulate_harmonic_point(const Network& network, double amplitude, double frequency, const HarmonicOptions& options, double preload) {
  HarmonicPoint point = steady_point(network, amplitude, frequency, options, preload);
  point.preload = preload;
  return point;
}

std::vector<HarmonicPoint> simulate_harmonic_grid(const Network& network, const std::vector<double>& amplitudes,
                                                  const std::vector<double>& frequencies, const HarmonicOptions& options, double preload) {
  std::vector<HarmonicPoint> points(amplitudes.size() * frequencies.size());
  parallel_for(points.size(), options.threads, [&](std::size_t i) {
    points[i] = simulate_harmonic_point(network, amplitudes[i / frequencies.size()], frequencies[i % frequencies.size()], options, preload);
  });
  return points;
}

namespace {

HarmonicPoint steady_point(const Network& network, double amplitude, double frequency, const HarmonicOptions& options, double preload) {
  // The measures divide by u0 and the cycle by f: a zero would be NaN in every column.
  if (!(amplitude > 0.0 && std::isfinite(amplitude) && frequency > 0.0 && std::isfinite(frequency)))
    throw std::logic_error(fmt::format("model '{}': a harmonic point needs a positive, finite amplitude and frequency, got {} mm and {} Hz",
                                       network.model().name, amplitude, frequency));
  if (uses_closed_form(network, options)) {
    if (options.steady_state == SteadyState::closed_form)
      return closed_form_harmonic_point(network, amplitude, frequency, options.definition, preload);
    if (auto point = try_closed_form_harmonic_point(network, amplitude, frequency, options.definition, preload)) return *point;
  }
  if (uses_sundials(network, options.solver)) {
    if (preload == 0.0) return dae_harmonic_point(network, amplitude, frequency, options);
    const StartAtRest start = relaxed_start(network, relaxed_state(network, preload));
    return dae_harmonic_point(network, amplitude, frequency, options, nullptr, preload, &start);
  }
  if (options.steady_state == SteadyState::closed_form)
    throw std::logic_error(
        fmt::format("model '{}' has non-linear elements inside nested series/parallel blocks, or quadratic_dashpot, gap or bouc_wen elements, "
                    "which have no closed-form periodic state; use steady_state = time_stepping (or auto)",
                    network.model().name));
  const int n = options.steps_per_cycle;
  const double period = 1.0 / frequency;
  const double dt = period / n;
  const double omega = 2.0 * std::numbers::pi * frequency;
  const Simulator simulator(network);
  const StepPlan plan = StepPlan::make(network, dt);
  const bool midpoints = network.topology().has_rate_jump;
  const StepPlan half_plan = midpoints ? StepPlan::make(network, 0.5 * dt, dt) : StepPlan{};

  State state = relaxed_state(network, preload);
  set_periodic_start(network, plan, amplitude, n, state, preload);
  State next = state, probe = state, cycle_start = state;
  std::vector<double> phase(static_cast<std::size_t>(n)), displacement(phase.size()), force(phase.size());
  std::vector<double> drive(phase.size());  // u at the end of step k [mm], the same every cycle
  for (int k = 0; k < n; ++k) drive[static_cast<std::size_t>(k)] = preload + amplitude * std::sin(omega * (k + 1) * dt);
  const bool needs_two_cycles = !network.topology().subtrees.empty();

  HarmonicPoint point;
  point.amplitude = amplitude;
  point.frequency = frequency;
  double previous_change = std::numeric_limits<double>::infinity();
  double previous_rate = 0.0;
  StallWatch stall;
  int first_check = 1;  // cycles after a skip that end before this one neither converge nor skip
  for (int cycle = 1; cycle <= options.max_cycles; ++cycle) {
    cycle_start.values = state.values;
    for (int k = 0; k < n; ++k) {
      const auto i = static_cast<std::size_t>(k);
      const double u_next = drive[i];
      if (midpoints) {
        const double u_mid = 0.5 * (state.u + u_next);
        phase[i] = omega * (k + 0.5) * dt;
        displacement[i] = u_mid;
        force[i] = simulator.step(half_plan, state, u_mid, probe, ((cycle - 1) * n + k + 0.5) * dt);
      }
      const double f = simulator.step(plan, state, u_next, next, ((cycle - 1) * n + k + 1) * dt);
      if (!midpoints) {
        phase[i] = omega * (k + 1) * dt;
        displacement[i] = u_next;
        force[i] = f;
      }
      std::swap(state, next);
    }
    // The drive returns to exactly p after a whole cycle.
    state.u = preload;
    const CycleSamples samples{phase, displacement, force};
    point.measures = measure_cycle(samples, amplitude, options.definition);
    point.cycles = cycle;
    const double force_scale = std::max(point.measures.force_amplitude, std::numeric_limits<double>::min());
    const CycleScales scales{force_scale, amplitude, omega * amplitude, period};
    const double change = cycle_change(network.topology(), cycle_start.values, state.values, scales);
    const double rate = change / previous_change;
    const double remaining = rate < 1.0 ? change * rate / (1.0 - rate) : change;
    previous_change = change;
    point.residual = std::max(change, remaining);
    if (change <= options.tolerance && (!needs_two_cycles || cycle >= 2) && cycle >= first_check && remaining <= options.tolerance) {
      point.converged = true;
      break;
    }
    if (cycle >= first_check) stall.add(cycle, options.max_cycles, change);  // not the cycle a skip ended
    point.stalled = cycle == options.max_cycles && stall.stalled(options.max_cycles);
    if (cycle >= first_check && steady_contraction(rate, previous_rate)) {
      skip_geometric_tail(cycle_start.values, rate, state.values);
      first_check = cycle + 2;
    }
    previous_rate = rate;
  }
  return point;
}

}  // namespace

}  // namespace rheo::runtime
