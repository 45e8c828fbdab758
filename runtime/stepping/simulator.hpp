// Fixed-step, displacement-driven simulation of a compiled network.
//
// The drive is piecewise linear between samples: over a step the terminal moves from u_n to
// u_{n+1} at constant rate. Under that drive every kernel is exact: springs and Yeoh springs
// are algebraic, Maxwell elements use the exact exponential update (leaf_kernels.hpp), friction
// elements and sliders the return mapping (sec. 2.4), quadratic dashpots the constant-rate
// force, gaps their stops, bouc_wen elements their loading law (closed form for n = 1, an
// order-5 Taylor series otherwise: bouc_wen.hpp); subtrees with internal nodes are solved implicitly
// (tree_solver.hpp). Stable for any ratio of step to relaxation time. Inerters, whose force
// is impulsive under a piecewise-linear drive, are second order (leaf_kernels.hpp).
//
// Structure (Network) is const and shared; a State is the only thing that changes. step() is
// a pure function of (plan, before, u_next) writing `after`: no allocation, no I/O, no
// virtual dispatch; the root kernels loop over flat per-kind arrays.
#pragma once

#include "runtime/network/leaf_kernels.hpp"
#include "runtime/network/network.hpp"
#include "runtime/stepping/tree_solver.hpp"

#include <limits>
#include <vector>

namespace rheo::runtime {

struct State {
  std::vector<double> values;  // layout in Topology (forces N, elongations mm)
  double u = 0.0;              // drive displacement at the last step [mm]
  double force = 0.0;          // total force at the last step [N]
};

// Constants of one step length.
struct StepPlan {
  double dt = 0.0;                           // s
  std::vector<double> maxwell_a, maxwell_b;  // root Maxwell elements: F <- a F + b du
  double dashpot_c_over_dt = 0.0;            // N/mm
  TreeStepPlan tree;
  // `piece`: the length of the linear piece of the drive that the step begins, when longer
  // than dt (see TreeStepPlan); 0: dt.
  static StepPlan make(const Network& network, double dt, double piece = 0.0);
};

class Simulator {
 public:
  explicit Simulator(const Network& network) : network_(network) {}

  const Network& network() const { return network_; }
  // Undeformed, unloaded: every elongation and force zero.
  State rest_state() const;
  // Advances `before` by plan.dt with the drive moving to u_next; writes `after` (which must
  // have the size of rest_state().values). Returns the total force [N] at the end of the step.
  // `time` [s], the time at the end of the step, only names the step in a NumericalError when
  // a subtree's solve exhausts its iteration cap (tree_solver.hpp).
  double step(const StepPlan& plan, const State& before, double u_next, State& after, double time = std::numeric_limits<double>::quiet_NaN()) const;
  // The root block's part of step(): writes its slots of `after` and returns its force [N];
  // the subtrees' slots, after.u and after.force are left as they are.
  double step_root(const StepPlan& plan, const State& before, double u_next, State& after) const;

  // Force [N] and elongation [mm] of every element the user wrote (Topology::probes order),
  // for the step that led from `before` to `after`.
  void element_outputs(const StepPlan& plan, const State& before, const State& after, std::vector<double>& force,
                       std::vector<double>& elongation) const;

 private:
  const Network& network_;
};

}  // namespace rheo::runtime
