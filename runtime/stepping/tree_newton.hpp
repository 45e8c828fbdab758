// The step of a subtree solved for all its unknowns at once by one Newton iteration (issue #26
// item 3).
//
// TreeSolver's nested solve composes step relations recursively: a series chain's force is a
// 1-D solve whose every evaluation inverts its parallel members, each a 1-D solve whose every
// evaluation runs the chains inside it, and so on, so that the work is the product of the
// levels' iteration counts (about 3^depth, and 1e4-1e6 member evaluations per step where a
// bouc_wen's inverse makes the inner solves noisy). Here the unknowns of all levels iterate
// together, one evaluation of every member per iteration whatever the depth:
//   chain c (series, given its increment de_c):  R_c = sum_i e_i(F_c) - de_c = 0,
//   block b (parallel in a chain, given F):       R_b = sum_j F_j(de_b) - F = 0,
//   member m (a bouc_wen in a chain, given F):    R_m = F_m(de_m) - F = 0,
// with the members' exact step relations (leaf_kernels.hpp, bouc_wen.hpp; linear and
// capped-linear blocks in closed form by TreeSolver). A bouc_wen in a chain is stepped forward
// (one march) rather than inverted (a march and a solve of its last substep). The Newton system
// is a tree, solved exactly by the composition that linear step relations use: bottom-up each
// node is linearised with the unknowns below it eliminated,
//   chain:  F ~ hat + K (de' - de),  K = 1 / sum_i C_i,  hat = F_c + (de - sum_i hat_i) K,
//   block:  e ~ hat + C (F' - F),    C = 1 / sum_j K_j,  hat = de_b + (F - sum_j hat_j) C,
// and top-down every unknown takes the value its parent's new one gives.
//
// Where a member or block holds most of its chain's compliance (a bouc_wen near saturation,
// dF/dde -> 0) the chain's step is solved for that pivot's elongation instead, and the chain's
// force follows the pivot's law there: in F the step would be 0 * inf, and F would creep to fy.
// So it is where the linear step leaves through a saturation end (bouc_wen's fy, or a block's
// sum of them): the member bounding the chain there is the pivot whatever its compliance (at
// de = 0 it is linearised on the unloading side; the force, held below the end, would never let
// it load). Saturated in double, a bouc_wen carries fy to the last bit: the chain's force then
// lies within an ulp of the end, just inside it (where a step also starts whose chain force the
// last step left on it), and the chain's linearised force may round beyond it.
//
// Set-valued relations are complementarity conditions, decided at every evaluation on the
// linearised elongations and forces: a chain at a cap some member reaches (friction element,
// slider) stays there while its members take up de below it (it slips, K = 0); a chain with gaps
// at F = 0 stays free (K = 0) while de lies within their play; a block rigid while stuck
// (sliders) at de = 0 stays stuck (C = 0) while F lies within its forces at zero rate. An
// iterate that would cross such a point, or a kink (friction elements and bouc_wen at de = 0,
// whose slope there is taken on the side the force asks for; a quadratic dashpot's inverse at
// F = 0), stops on it; one that would leave the forces a chain can carry (bouc_wen's +-fy, a
// softening spring's peak) goes half way to the bound, never onto it. Globalised by a
// backtracking line search on the squared residuals in the subtree's force and elongation
// scales; where no step along the direction lowers it (a tangent from the wrong side of a kink)
// a few full steps are taken. Where no unknown moves by more than its rounding (a chain's force
// also not where that moves its elongations by more than 1e4 tolerances: a quadratic dashpot's
// near F = 0) a step within 1e4 tolerances is taken as converged.
//
// Converged when every residual is within kRelTol of its scale (the node's, and no finer than
// the subtree's) plus what rounding of its unknown leaves (F's last bit times the compliance of
// the members whose elongation follows from it). The member with the largest compliance then
// takes the rounding remainder of its chain's elongation (the slipping member at a cap, the gaps
// within their play), so that no member's elongation carries another's error, and a bouc_wen's
// force is stored as its law's at its elongation. Increments start from those of the plan's last
// step scaled by the ratio of the subtree's increments (a secant predictor), chain forces from
// their forces before the step.
//
// Where that start is 0 (a fresh plan, after a rest or a fallback) and a member's law has no
// slope there, the first update is far off: with quadratic dashpots at rest (q de |de|, slope 0
// at de = 0) a block of them holds the chain's whole compliance, pivots its step with the whole
// increment, and the solve diverges from a force 10^2 times the answer (differential seed 61,
// model 157, reproducer 14: the first step of its history at 37 us; two blocks of quadratic
// dashpots in series, tree_newton_test). A step that does not converge from its start is solved
// once more from the secant start: the increment split down the tree as a linear network of the
// nodes' secant stiffnesses over the subtree's increment, (F(de) - F(0)) / de (a quadratic
// dashpot's q |de| over it, not 0), which converges there in 9 iterations. A step that does not
// converge from either start within NewtonLayout::max_iterations (or the plan's lowered
// iteration cap) falls back to TreeSolver's nested solve, which is exact where it converges and
// whose errors (an exhausted cap, a softening spring asked for more than its peak) name the
// element. Rare: none in about 23000 steps of random networks of every element kind to depth 6 (1
// before the saturation ends above), none on the differential test's networks whose bouc_wen
// chains saturate in double (tree_newton_test, docs/numerics.md). No allocation: the scratch is
// the plan's NewtonWork.
#pragma once

#include "runtime/stepping/tree_solver.hpp"

namespace rheo::runtime {

class TreeNewton {
 public:
  TreeNewton(const TreeSolver& solver, const TreeStepPlan& plan) : s_(solver), layout_(plan.newton), w_(plan.work), cap_(plan.iteration_cap) {}

  // Solves subtree `root` (NewtonLayout::iterative) for the increment de, writes every node's
  // state into `after` and the subtree's force into `force`; false if it did not converge
  // (then the caller's nested solve overwrites whatever was written).
  bool advance(int root, double de, double* after, double& force);

 private:
  enum State : std::int8_t { regular, play, slip_hi, slip_lo, stuck, leave_up, leave_down };
  struct Lin {
    double out, hat, tangent;
  };

  bool solve(int root, double de, double* after, double& force);
  void start(int node, double ratio);  // the first iterate
  void remember(int node);             // the converged changes, for the next step's start
  // The secant start: each node's secant stiffness [N/mm] over the subtree's increment de
  // (F(de) - F(0)) / de, blocks adding, chains adding compliances, into `target`; then de split
  // down the tree by them into the blocks' and members' increments.
  double secant(int node, double de);
  void share(int node, double de);
  double evaluate(int root, double de);  // the merit; sets converged_
  Lin forward(int node, double de);
  Lin inverse(int node, double force);
  Lin chain(int node, double de);
  Lin block(int node, double force);
  Lin member(int node, double force);
  void update_forward(int node, double de);
  void update_inverse(int node, double force);
  void assign_forward(int node, double de, double* after);
  void assign_inverse(int node, double e, double force, double* after);
  void assign_chain(int node, double de, double* after);
  void assign_stuck(int node, double force, double* after);
  // Adds residual r of a node (`force`: in N, else in mm) to the merit, and to the test of
  // convergence: |r| within kRelTol of `scale` plus `rounding` (what rounding the node's unknown
  // leaves).
  void residual(double r, double scale, double rounding, bool force);
  int most_compliant(int chain) const;            // the member that takes the rounding remainder
  int saturating(int chain, double force) const;  // the member bounding the saturation end `force` reaches (-1: none)
  double pivot_force(int node, double de) const;  // a pivot's force at increment de (its law)

  double& at(std::vector<double>& v, int node) const { return v[static_cast<std::size_t>(node)]; }
  std::int8_t& state(int node) const { return w_.state[static_cast<std::size_t>(node)]; }
  NewtonRole role(int node) const { return layout_.role[static_cast<std::size_t>(node)]; }
  const TreeNode& node(int n) const { return s_.at(n); }

  const TreeSolver& s_;
  const NewtonLayout& layout_;
  NewtonWork& w_;
  int cap_;
  double force_scale_ = 1.0, length_scale_ = 1.0;  // N, mm (solve)
  double merit_ = 0.0;
  double worst_ = 0.0;  // the largest residual of the last evaluation, in tolerances
  bool converged_ = true;
};

}  // namespace rheo::runtime
