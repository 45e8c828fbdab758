// A point of a harmonic test, u = p + u0 sin(2 pi f t) (p the preload, usually 0): how its periodic steady state is found
// (HarmonicOptions) and what characterises it (HarmonicPoint, cycle_measures.hpp). The runner
// that finds it is protocols/harmonic.hpp.
#pragma once

#include <algorithm>
#include <cmath>

#include "runtime/core/cycle_measures.hpp"
#include "lang/protocol_settings.hpp"

namespace rheo::runtime {

using lang::SolverChoice;  // the `solver` setting's vocabulary (lang/protocol_settings.hpp)

// How the periodic state is found: `automatic` uses the closed form of
// periodic_closed_form.hpp where the network allows it (non-linear elements only in the root
// parallel block) unless the solver is explicitly `sundials`, and time stepping otherwise;
// `closed_form` insists on it (std::logic_error when the network has none: callers check
// has_closed_form_periodic_state first); `time_stepping` always steps. (The `steady_state`
// setting's vocabulary.)
using lang::SteadyState;

struct HarmonicOptions {
  HarmonicDefinition definition = HarmonicDefinition::thesis;
  SteadyState steady_state = SteadyState::automatic;
  int steps_per_cycle = lang::HarmonicSettings::default_steps_per_cycle;  // N, a multiple of 4 (turning points sampled)
  int max_cycles = lang::HarmonicSettings::default_cycles_max;
  double tolerance = lang::HarmonicSettings::default_tolerance;
  SolverChoice solver = SolverChoice::automatic;
  int threads = 1;  // grid and fit points evaluated at once (runtime/core/parallel_for.hpp; <= 0: all)
};

struct HarmonicPoint {
  double amplitude = 0.0;  // u0 [mm]
  double preload = 0.0;    // p [mm]: the drive is u = p + u0 sin(2 pi f t), from the relaxed state at p
  double frequency = 0.0;  // f [Hz]
  CycleMeasures measures;
  int cycles = 0;  // simulated cycles (0: closed form; event-driven branches: the cycles their shooting followed)
  bool converged = false;
  double residual = 0.0;  // estimated relative distance from the periodic state
  // Not converged, and the state's change over a cycle, over the last quarter of the cycles, is
  // at least half what it was over the second quarter (StallWatch): the state is
  // not approaching a periodic one within reach (an undamped free oscillation, which has no
  // unique periodic state, or a mode far slower than cycles_max periods).
  bool stalled = false;
  // A geometric skip of the state's slow part (ComponentSettling) led where the integrator found
  // no consistent state, and was undone: a drift taken for a slow contraction, such as a slider
  // that ratchets (it slips further one way every cycle, in a chain with no static stiffness).
  bool skip_refused = false;
};

// Watches the state's change over each cycle of a point for `stalled` (at least 4 cycles): the
// geometric means of the changes over the second and over the last quarter of the cycles (a
// mean of logarithms, so that the jump of a skipped geometric tail does not dominate).
struct StallWatch {
  double second_quarter = 0.0, last_quarter = 0.0;  // sums of ln(change)
  int second_count = 0, last_count = 0;
  void add(int cycle, int max_cycles, double change) {
    const double log_change = std::log(std::max(change, 1e-300));
    if (4 * cycle > max_cycles && 2 * cycle <= max_cycles) second_quarter += log_change, ++second_count;
    if (4 * cycle > 3 * max_cycles) last_quarter += log_change, ++last_count;
  }
  bool stalled(int max_cycles) const {
    return max_cycles >= 4 && second_count > 0 && last_count > 0 && last_quarter / last_count >= std::log(0.5) + second_quarter / second_count;
  }
};

}  // namespace rheo::runtime
