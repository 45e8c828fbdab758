// A point of a harmonic test, u = p + u0 sin(2 pi f t) (p the preload, usually 0): how its periodic steady state is found
// (HarmonicOptions) and what characterises it (HarmonicPoint, cycle_measures.hpp). The runner
// that finds it is protocols/harmonic.hpp.
#pragma once

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
};

}  // namespace rheo::runtime
