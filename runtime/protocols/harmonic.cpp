#include "runtime/protocols/harmonic.hpp"

#include "runtime/protocols/cycle_groups.hpp"

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
  CycleGroups groups(network.topology());
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
    const double change = groups.measure(cycle_start.values, state.values, scales);
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
    if (cycle >= first_check && groups.skip_contracting(cycle_start.values, state.values)) first_check = cycle + 2;
  }
  return point;
}

}  // namespace

}  // namespace rheo::runtime
