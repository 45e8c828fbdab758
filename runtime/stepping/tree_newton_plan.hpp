// What the global Newton solve of a subtree step (tree_newton.hpp) knows about each node before
// a step (NewtonLayout, from the topology and the parameters), and its scratch (NewtonWork).
#pragma once

#include "runtime/network/network.hpp"

#include <cstdint>
#include <vector>

namespace rheo::runtime {

struct Interval {
  double lo, hi;
};

// How a node takes part in the global solve. A node is evaluated forward (given its elongation
// increment, its force) when its parent is a parallel block or it is the subtree's root, and
// inverted (given its force, its elongation increment) when its parent is a series chain.
enum class NewtonRole : std::uint8_t {
  closed,  // evaluated by TreeSolver without an iteration of this solve: leaves, linear blocks,
           // capped-linear chains and chains of members rigid while stuck
  sum,     // a parallel block evaluated forward (the subtree's root): forces add
  chain,   // a series chain evaluated forward: its common force is an unknown
  block,   // a parallel block inside a chain: its common elongation increment is an unknown
  member,  // a bouc_wen in a chain: its elongation increment is an unknown (the law is stepped
           // forward, one march, rather than inverted, a march and a solve of its last substep)
};

struct NewtonLayout {
  std::vector<NewtonRole> role;  // per node
  // Per chain: the forces its members can carry, [lo, hi] [N]: the chain's cap (friction
  // elements, sliders, bouc_wen) intersected with the peaks of its yeoh and poly_spring members.
  std::vector<Interval> domain;
  // Per chain: whether the domain's end is a cap some member reaches (a friction element or
  // slider slips there: the chain's force stays at it while the rest slides) or one only
  // approached (bouc_wen saturating, a softening spring's peak: an open end).
  std::vector<std::uint8_t> reaches_hi, reaches_lo;
  // Per chain: whether an open end is a bouc_wen's fy (or a sum of them across a block), which
  // its members approach as they saturate and reach in rounding: the chain has a solution for
  // every increment, its force within an ulp of the end once they saturate in double. The other
  // open ends are a softening spring's peak, beyond which it has none.
  std::vector<std::uint8_t> saturates_hi, saturates_lo;
  // Per node: a stiffness [N/mm] typical of the subtree below it (the sum of its members'
  // elastic and viscous stiffnesses at this step), which floors a block's tangent stiffness and
  // a chain's tangent compliance where every member is at a cap or rigid.
  std::vector<double> stiffness;
  // Per node: a member or block, which can be a chain's pivot where its compliance dominates
  // (tree_newton.hpp).
  std::vector<std::uint8_t> pivot;
  // Per block: a friction element or bouc_wen among its members (a kink at de = 0); per chain:
  // a gap or quadratic_dashpot among them (a kink, or a singular inverse, at F = 0).
  std::vector<std::uint8_t> kinked;
  // Per node: how many nodes its subtree holds (they follow it in Topology::nodes).
  std::vector<int> extent;
  // Per subtree root (by node): whether its step needs this solve (it has a chain or a block).
  std::vector<std::uint8_t> iterative;
  // Newton iterations a step may take before it falls back to the nested solve (TreeSolver).
  static constexpr int max_iterations = 60;

  // `bounds`, `coefficient`: TreeStepPlan's (its caps; a yeoh's largest force).
  void prepare(const Network& network, const std::vector<Interval>& bounds, const std::vector<double>& coefficient);
};

// Per-node scratch of one step's solve (sized by NewtonLayout::prepare's caller; no allocation
// while stepping). `x` are the unknowns (a chain's force [N], a block's or member's elongation
// increment [mm]), `target` the values the Newton update proposes for them; `input` each node's given value at the last evaluation (its elongation increment
// forward, its force inverted); `out` its exact answer there; `hat` and `tangent` its
// linearisation with every unknown below eliminated: answer ~ hat + tangent (input' - input).
struct NewtonWork {
  std::vector<double> x, saved, target, input, out, hat, tangent;
  std::vector<double> load;   // a member's or block's force at its iterate [N]
  std::vector<double> slope;  // and its tangent stiffness there [N/mm], not floored
  // Per block or member: its elongation increment over the plan's last step [mm]; per subtree
  // root: that step's increment [mm]. The next step's start.
  std::vector<double> last, last_de;
  // Per node: the evaluation's regime (NewtonWork::State values).
  std::vector<std::int8_t> state;
  // Counts for tests and benchmarks: steps solved here, evaluations of every member they took,
  // steps solved again from the secant start (tree_newton.hpp) and steps that fell back to the
  // nested solve.
  long solves = 0, evaluations = 0, restarts = 0, fallbacks = 0;
  void resize(std::size_t nodes);
};

}  // namespace rheo::runtime
