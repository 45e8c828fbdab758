// Steps a network along a displacement drive given sample by sample, on the fixed-step kernels
// (simulator.hpp): sample 0 is the relaxed state at the first displacement (relaxed_state.hpp),
// each further sample one step from the one before. A new StepPlan is made where the step
// length changes by more than a relative 1e-9. Whether the drive arrives whole (run_history.hpp)
// or in pieces (stream_history.hpp), the same calls make the same numbers.
// No allocation, I/O or virtual dispatch per step once the plan is made.
#pragma once

#include "runtime/network/network.hpp"
#include "runtime/stepping/simulator.hpp"

#include <vector>

namespace rheo::runtime {

class DriveStepper {
 public:
  // ELEMENTS: also every element's force and elongation (Topology::probes order) per sample.
  DriveStepper(const Network& network, bool elements);

  // Sample 0, at displacement U0 [mm] and time T0 [s]: the relaxed state. Returns its force [N].
  double start(double t0, double u0);
  // The next sample, at time T [s] (after the last) and displacement U [mm]. Returns its force
  // [N]. NumericalError where a subtree's solve fails (tree_solver.hpp).
  double step(double t, double u);

  // The last sample's element forces [N] and elongations [mm] (with ELEMENTS).
  const std::vector<double>& element_force() const { return element_force_; }
  const std::vector<double>& element_elongation() const { return element_elongation_; }

 private:
  const Network& network_;
  Simulator simulator_;
  bool elements_;
  StepPlan plan_;
  State state_, next_;
  double time_ = 0.0;
  std::vector<double> element_force_, element_elongation_;
};

}  // namespace rheo::runtime
