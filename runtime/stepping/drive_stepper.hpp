// Steps a network along a displacement drive given sample by sample, on the fixed-step kernels
// (simulator.hpp): sample 0 is the relaxed state at the first displacement (relaxed_state.hpp),
// each further sample one step from the one before. A new StepPlan is made where the step
// length changes by more than a relative 1e-9. Whether the drive arrives whole (run_history.hpp)
// or in pieces (stream_history.hpp), the same calls make the same numbers.
// No allocation, I/O or virtual dispatch per step once the plans are made.
//
// Error control. The root block's kernels are exact under the drive's linear pieces; a subtree
// with internal nodes is solved as if each of its elements' elongations moved linearly over the
// step (tree_solver.hpp): implicit Euler, first order, where an internal node's motion is not
// linear (a spring and a dashpot in series with c/k = 0.16 ms on a 1 kHz drive: 11 % of max |F|
// at the first sample, 2 % later, against IDA). Where the network has a subtree with a dashpot,
// Maxwell element or quadratic dashpot whose step is not exact (drive_stepper.cpp, controlled:
// not a slider-capped Maxwell arm, no inerter), each interval is taken as one step and as two
// half steps (step doubling). Where the force of a node of those subtrees, or a gap's elongation
// in them times their springs' stiffness (where the gap shuts next follows from it), differs
// between them by more than `tolerance` times the largest |F| so far (a tenth of it for a subtree
// that is not linear), each half is treated so in turn, down to 2^kMaxHalvings steps an
// interval. A linear subtree (springs, dashpots, Maxwell elements) keeps 2 x halves - one step
// (the extrapolated implicit Euler step: second order, L-stable); another keeps the halves, whose
// first-order error is about their difference. Other networks step once an interval, bit for bit as without the
// control (docs/numerics.md, "Error control of fixed-step histories").
#pragma once

#include "runtime/network/network.hpp"
#include "runtime/stepping/simulator.hpp"

#include <vector>

namespace rheo::runtime {

class DriveStepper {
 public:
  // Error control's relative tolerance by default, and its deepest halving (256 steps an interval).
  static constexpr double kDefaultTolerance = 1e-3;
  static constexpr int kMaxHalvings = 8;

  // ELEMENTS: also every element's force and elongation (Topology::probes order) per sample.
  // TOLERANCE: of the error control above, relative to the largest |F| so far; 0 takes one step
  // an interval on every network.
  DriveStepper(const Network& network, bool elements, double tolerance = kDefaultTolerance);

  // Sample 0, at displacement U0 [mm] and time T0 [s]: the relaxed state. Returns its force [N].
  double start(double t0, double u0);
  // The next sample, at time T [s] (after the last) and displacement U [mm]. Returns its force
  // [N]. NumericalError where a subtree's solve fails (tree_solver.hpp).
  double step(double t, double u);

  // The last sample's element forces [N] and elongations [mm] (with ELEMENTS).
  const std::vector<double>& element_force() const { return element_force_; }
  const std::vector<double>& element_elongation() const { return element_elongation_; }
  // Steps taken since start(), halves included (one an interval without error control).
  long steps() const { return steps_; }

 private:
  // Advances FROM over the interval that ends at time T [s] and displacement U [mm], of which
  // COARSE is the one step at `level`'s length (2^-level of the sample's), into TO.
  void refine(int level, const State& from, double t, double u, const State& coarse, State& to);
  const StepPlan& plan_at(int level);

  const Network& network_;
  Simulator simulator_;
  bool elements_;
  double tolerance_;          // 0: no error control
  struct Controlled {         // a subtree one step may not give exactly
    int first = 0, last = 0;  // its state slots [first, last)
    bool linear = false;      // only springs, dashpots and Maxwell elements: extrapolated
    std::vector<int> forces;  // the force slot of each of its nodes, its root's first
    std::vector<int> gaps;    // the elongation slot of each of its gaps
    double stiffness = 0.0;   // its springs' stiffnesses summed [N/mm]: a gap's elongation error as a force
  };
  std::vector<Controlled> controlled_;
  StepPlan plan_;                 // the sample's step
  std::vector<StepPlan> halves_;  // plan_ halved 1, 2, ... times, made as first needed
  int halves_made_ = 0;
  State state_, next_;
  std::vector<State> mid_, end_, fine_, coarse_;  // per level of refine()
  const State* last_from_ = nullptr;              // the last step's start and length, for element outputs
  const StepPlan* last_plan_ = nullptr;
  double time_ = 0.0;
  double peak_ = 0.0;  // largest |F| so far [N]
  long steps_ = 0;
  std::vector<double> element_force_, element_elongation_;
};

}  // namespace rheo::runtime
