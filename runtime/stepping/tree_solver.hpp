// Implicit step solution of nested series/parallel subtrees.
//
// Every node's step relation F(de) (force at the end of the step against its elongation
// increment over the step) is monotone non-decreasing, so composition is well posed:
//   parallel: F(de) = sum_i F_i(de)                  (common elongation, forces add)
//   series:   de(F) = sum_i de_i(F)                  (common force, elongations add)
// A series chain's F(de) is found by a safeguarded Newton iteration on de(F) = de in the
// common force; a parallel block inside a chain is inverted the same way in de. Capped members
// (friction elements, sliders) bound the chain force to [lo, hi]; when the chain cannot take
// up de below the cap, the capped member slips and absorbs the rest: the return mapping of
// section 2.4 generalised to chains with internal nodes. Rigid-plastic sliders make a relation
// set-valued at de = 0; that case is resolved exactly from the force interval at zero rate. Caps
// may be one-sided (fy_pos in tension, fy_neg in compression): every bound is an interval.
// Gaps (direct members of chains only, network.hpp) are the dual: their inverse is set-valued
// at F = 0 (any elongation in [c - w/2, c + w/2], c its center) and rigid otherwise
// (e = c +- w/2). A chain with gaps
// first tests whether de is reachable at F = 0, the gaps spanning their play: then F = 0 exactly
// and the gaps take what the other members leave; otherwise it is solved on the side of F = 0
// that de lies on, each gap at its end stop with zero compliance.
//
// Linear subtrees (springs, dashpots, Maxwell elements, inerters) have affine step relations,
// F(de) = F0 + S de, and so do their compositions:
//   parallel: F0 = sum F0_i, S = sum S_i;   series: S = 1 / sum(1/S_i), F0 = S sum(F0_i/S_i);
// they are evaluated bottom-up without iteration. A capped-linear chain (linear members,
// friction elements within their caps acting as springs of force F_n, sliders rigid) is
// F(de) = clamp(F0 + S de, cap): the return mapping of eq. 2.9 with the chain as the spring.
//
// Subtrees whose chains iterate are first solved for all their unknowns at once by one global
// Newton iteration (tree_newton.hpp), which evaluates every member once per iteration whatever
// the depth; the nested solve above is its fallback and, in tests, its second path.
//
// No allocation: recursion over the flat node array, state read from `before`.
//
// Bounded: every iteration (solve_monotone, the bouc_wen law) has an iteration cap; a solve
// that exhausts one throws a NumericalError naming the element (or block) and the time of the
// step, never hangs or returns an unconverged value.
#pragma once

#include "runtime/network/bouc_wen.hpp"
#include "runtime/network/leaf_kernels.hpp"
#include "runtime/network/monotone_solve.hpp"
#include "runtime/network/network.hpp"
#include "runtime/stepping/tree_newton_plan.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace rheo::runtime {

// Per-step constants of subtree leaves (depend on dt).
struct TreeStepPlan {
  double dt = 0.0;  // s
  // Length [s] of the linear piece of the drive that the step begins (>= dt): dt except for the
  // harmonic protocol's midpoint probes (half a step along a piece of 2 dt).
  double piece = 0.0;
  std::vector<MaxwellStep> maxwell;  // per node (unused entries for other kinds)
  // Per node: dashpot c/dt [N/mm], quadratic_dashpot cq/dt^2 [N/mm^2], inerter 4 b/dt^2 [N/mm],
  // yeoh the largest force [N] it carries before its tangent reaches zero (infinite if never).
  std::vector<double> coefficient;
  // Per node: the forces [N] it can carry (caps of friction elements, sliders and bouc_wen,
  // intersected along series chains, added across parallel blocks); unbounded otherwise.
  std::vector<Interval> bounds;
  // Refinement iterations each solve may take (solve_monotone, and the global Newton
  // iterations of tree_newton.hpp); lowered only by tests.
  int iteration_cap = kRefineSteps;
  // Subtrees with series chains or blocks to iterate are solved for all their unknowns at once
  // (tree_newton.hpp), falling back to the nested solve below. `global_newton = false` takes
  // the nested solve alone: tests compare the two paths.
  NewtonLayout newton;
  bool global_newton = true;
  // A friction element is inverted within its cap (the force it is asked for clamped to it).
  // In a capped-linear chain that clamp never binds (the chain's force lies within the cap);
  // `clamp_friction = false` drops it, so that such a chain's step is affine in the state on
  // any state: JumpHoldStep reads its maps off unit states (jump_hold.hpp).
  bool clamp_friction = true;
  // That solve's scratch: a plan serves one thread at a time.
  mutable NewtonWork work;
  void prepare(const Network& network, double dt, double piece);
};

// Whether every subtree steps without iteration: each series chain linear, capped-linear or
// rigid while stuck (its parallel blocks then are only evaluated forward, never inverted).
bool steps_without_iteration(const Topology& topology);

class TreeSolver {
 public:
  // `time`: the time [s] at the end of the step, for error messages (NaN: not known).
  TreeSolver(const Network& network, const TreeStepPlan& plan, const double* before, double time)
      : topology_(network.topology()), network_(network), plan_(plan), before_(before), time_(time) {}

  // Force at the end of the step for an elongation increment de of subtree `node`.
  double force(int node, double de) const { return forward(node, de).force; }

  // Solves the subtree for increment de and writes every node's new state into `after`.
  // Returns the subtree force.
  double advance(int node, double de, double* after) const;

  int child(const TreeNode& n, int i) const { return topology_.children[static_cast<std::size_t>(n.first_child + i)]; }

 private:
  friend class TreeNewton;
  // The nested solve of `advance` (recursive 1-D solves), without the global Newton solve.
  double advance_nested(int node, double de, double* after) const;
  ForceSlope forward(int node, double de) const;
  // A leaf's force at de = 0 and its slope on the side of `direction` (> 0: lengthening): one-
  // sided where the law has a kink there (a friction element at its cap, bouc_wen reversing).
  ForceSlope forward_at_rest(int node, double direction) const;
  ForceSlope affine(int node) const;  // {F0 [N], S [N/mm]} of a linear node
  ForceSlope capped_linear(int node, double de, Interval cap) const;
  ForceSlope inverse(int node, double force) const;  // {elongation increment, d de / dF}
  Interval bounds(int node) const { return plan_.bounds[static_cast<std::size_t>(node)]; }
  Interval zero_rate_interval(int node) const;  // forces admissible at de = 0 (rigid nodes)
  ForceSlope series_force(int node, double de) const;
  ForceSlope parallel_elongation(int node, double force) const;
  Interval play(const TreeNode& n) const;  // increments of a chain reachable at F = 0
  // A gap's end stops [mm]: e = center -+ width/2.
  Interval stops(const TreeNode& gap) const {
    const double c = gap_center(p(gap, 0), p(gap, 1));
    return {c - 0.5 * p(gap, 0), c + 0.5 * p(gap, 0)};
  }
  bool has_gap(const TreeNode& n) const;
  void assign(int node, double de, double force, double* after) const;
  void assign_inerter(int node, double de, double* after) const;
  void assign_parallel(const TreeNode& n, double de, double force, double* after) const;
  void assign_series(int node, double de, double force, double* after) const;
  void assign_play(const TreeNode& n, double de, double* after) const;
  ForceSlope inerter(int node, double de) const;
  // NumericalError: a yeoh in series asked for more force than it carries before softening.
  [[noreturn]] void throw_softened(int node, double force) const;
  // NumericalError: the solve of `node` exhausted its iteration cap (solve_monotone, bouc_wen).
  [[noreturn]] void throw_not_converged(int node, const char* what) const;
  double checked(double value, int node, const char* what) const {
    if (std::isnan(value)) throw_not_converged(node, what);
    return value;
  }
  std::string path_of(int node) const;

  const TreeNode& at(int node) const { return topology_.nodes[static_cast<std::size_t>(node)]; }
  double e_before(const TreeNode& n) const { return before_[n.state]; }
  double f_before(const TreeNode& n) const { return before_[n.state + 1]; }
  double slot_before(const TreeNode& n, int slot) const { return before_[n.state + slot]; }
  double coefficient(int node) const { return plan_.coefficient[static_cast<std::size_t>(node)]; }
  double p(const TreeNode& n, int slot) const { return network_.parameter(n.param[slot]); }

  const Topology& topology_;
  const Network& network_;
  const TreeStepPlan& plan_;
  const double* before_;
  double time_;
};

}  // namespace rheo::runtime
