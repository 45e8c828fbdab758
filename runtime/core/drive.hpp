// Displacement drives of the time-domain protocols (thesis section 4.3) and the histories
// simulated from them (protocols/run_history.hpp). A drive is a sequence of samples (t_k, u_k),
// linear between samples, from t = 0; the network starts relaxed at u_0 (at rest where u_0 = 0,
// as for every drive made here).
#pragma once


#include <string>
#include <vector>

namespace rheo::runtime {

struct Drive {
  std::vector<double> time;          // s, strictly increasing, time[0] = 0
  std::vector<double> displacement;  // mm; displacement[0]: where the network starts relaxed
};

// Triangle 0 -> +A -> 0 -> -A -> 0 at constant velocity v [mm/s], `cycles` per amplitude, the
// amplitudes in the order given (the thesis tests the highest first), `steps_per_cycle`
// samples per cycle (a multiple of 4; the data sets use 400).
Drive static_triangle(const std::vector<double>& amplitudes, double velocity, int cycles, int steps_per_cycle);
// Sine u = A sin(2 pi f t), `cycles` per amplitude, amplitudes in the order given.
Drive quasistatic_sine(const std::vector<double>& amplitudes, double frequency, int cycles, int steps_per_cycle);
// Relaxation: ramp to `amplitude` over `rise`, hold until `duration`, sampled every dt.
Drive step_relaxation(double amplitude, double rise, double duration, double dt);
// Splits every interval of `drive` into `substeps` equal steps (exact for a linear drive).
Drive refine(const Drive& drive, int substeps);

// A drive's start away from rest: the terminal force [N] and the force [N] and elongation [mm]
// of every element the user wrote (Topology::probes order), rates zero (the relaxed start:
// stepping/relaxed_state.hpp), for the integrators that take it.
struct StartAtRest {
  double force = 0.0;
  std::vector<double> element_force, element_elongation;
};

struct History {
  std::vector<double> time, displacement, force;
  std::vector<std::string> element_paths;
  std::vector<std::vector<double>> element_force, element_elongation;  // [element][sample]
};

}  // namespace rheo::runtime
