#include "runtime/stepping/drive_stepper.hpp"

#include "runtime/stepping/relaxed_state.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace rheo::runtime {
namespace {

constexpr double kUnextrapolatedWeight = 10.0;

bool rate_dependent(NodeKind kind) { return kind == NodeKind::dashpot || kind == NodeKind::maxwell || kind == NodeKind::quadratic_dashpot; }

// Whether the error control steps the subtree below ROOT with halves (drive_stepper.hpp): it
// holds an element whose force depends on a rate, so that an internal node may curve within a
// step, unless
//   - it is a series chain of one dashpot or Maxwell element with sliders: the element moves
//     linearly while the sliders hold and carries their yield force while they slip (exact; a
//     gap is not: the step in which it shuts spreads the element's elongation over the whole
//     step, 2 % of max |F| at that sample for a 2.3 ms Maxwell pair behind a gap at 1 kHz);
//   - it holds an inerter: Newmark's second-order step (tree_solver.hpp). Where the samples
//     resolve the mass's period, halving it converges, but slowly where the mass rings: a column
//     of 1.4 kg behind 300 N/mm (74 Hz, damping ratio 0.08) sampled at 1 kHz took 35 steps a
//     sample to go from 2.8 % to 0.25 % of max |F|, 386 for 0.02 %; where they do not (a column
//     refitted in a diagnosis of slow triangles sampled at 5-30 Hz), it would halve to the
//     deepest level at every kink of the drive. `solver = auto` takes IDA for networks with
//     inerters; `substeps` resolves a mass on fixed steps.
// Subtrees without a rate-dependent element (springs, yeoh and polynomial springs, friction
// elements, sliders, gaps, bouc_wen) are solved algebraically at the step's end: exact.
bool controlled(const Topology& t, int root) {
  int rate_members = 0, others = 0;
  bool inerter = false, chain_of_leaves = t.nodes[static_cast<std::size_t>(root)].kind == NodeKind::series;
  const auto visit = [&](const auto& self, int node) -> void {
    const TreeNode& n = t.nodes[static_cast<std::size_t>(node)];
    inerter |= n.kind == NodeKind::inerter;
    if (rate_dependent(n.kind)) ++rate_members;
    else if (n.kind != NodeKind::series && n.kind != NodeKind::parallel && n.kind != NodeKind::slider) ++others;
    if (node != root && (n.kind == NodeKind::series || n.kind == NodeKind::parallel)) chain_of_leaves = false;
    for (int i = 0; i < n.child_count; ++i) self(self, t.children[static_cast<std::size_t>(n.first_child + i)]);
  };
  visit(visit, root);
  if (rate_members == 0 || inerter) return false;
  return !(chain_of_leaves && rate_members == 1 && others == 0);
}

}  // namespace

DriveStepper::DriveStepper(const Network& network, bool elements, double tolerance)
    : network_(network), simulator_(network), elements_(elements), tolerance_(tolerance) {
  const std::size_t probes = elements ? network.topology().probes.size() : 0;
  element_force_.assign(probes, 0.0);
  element_elongation_.assign(probes, 0.0);
  const Topology& t = network.topology();
  for (int root : t.subtrees) {
    if (!controlled(t, root)) continue;
    const TreeNode& r = t.nodes[static_cast<std::size_t>(root)];
    Controlled c{r.state, r.state + r.slots, r.linear, {}, {}, 0.0};
    const auto span = [&](const auto& self, int node) -> void {
      const TreeNode& n = t.nodes[static_cast<std::size_t>(node)];
      c.first = std::min(c.first, n.state);
      c.last = std::max(c.last, n.state + n.slots);
      c.forces.push_back(n.state + 1);
      if (n.kind == NodeKind::gap) c.gaps.push_back(n.state);
      if (n.kind == NodeKind::spring || n.kind == NodeKind::maxwell || n.kind == NodeKind::friction || n.kind == NodeKind::poly_spring)
        c.stiffness += std::abs(network.parameter(n.param[0]));
      if (n.kind == NodeKind::yeoh) c.stiffness += 2.0 * std::abs(network.parameter(n.param[0]));
      for (int i = 0; i < n.child_count; ++i) self(self, t.children[static_cast<std::size_t>(n.first_child + i)]);
    };
    span(span, root);
    controlled_.push_back(c);
  }
  if (controlled_.empty()) tolerance_ = 0.0;
  if (tolerance_ > 0.0) {
    const State rest = simulator_.rest_state();
    halves_.resize(kMaxHalvings);
    for (auto* states : {&mid_, &end_, &fine_, &coarse_}) states->assign(kMaxHalvings, rest);
  }
}

double DriveStepper::start(double t0, double u0) {
  state_ = relaxed_state(network_, u0);
  next_ = state_;
  time_ = t0;
  plan_ = StepPlan{};
  halves_made_ = 0;
  peak_ = std::abs(state_.force);
  steps_ = 0;
  if (elements_ && u0 != 0.0) {
    const StartAtRest start = relaxed_start(network_, state_);
    element_force_ = start.element_force;
    element_elongation_ = start.element_elongation;
  } else {
    std::fill(element_force_.begin(), element_force_.end(), 0.0);
    std::fill(element_elongation_.begin(), element_elongation_.end(), 0.0);
  }
  return state_.force;
}

double DriveStepper::step(double t, double u) {
  const double dt = t - time_;
  if (!(dt > 0.0)) throw std::logic_error("drive time must increase strictly");
  if (plan_.dt == 0.0 || std::abs(dt - plan_.dt) > 1e-9 * dt) {
    plan_ = StepPlan::make(network_, dt);
    halves_made_ = 0;
  }
  simulator_.step(plan_, state_, u, next_, t);
  ++steps_;
  last_from_ = &state_;
  last_plan_ = &plan_;
  if (tolerance_ > 0.0) refine(0, state_, t, u, next_, next_);
  if (elements_) simulator_.element_outputs(*last_plan_, *last_from_, next_, element_force_, element_elongation_);
  std::swap(state_, next_);
  time_ = t;
  peak_ = std::max(peak_, std::abs(state_.force));
  return state_.force;
}

const StepPlan& DriveStepper::plan_at(int level) {
  if (level == 0) return plan_;
  for (; halves_made_ < level; ++halves_made_)
    halves_[static_cast<std::size_t>(halves_made_)] = StepPlan::make(network_, std::ldexp(plan_.dt, -(halves_made_ + 1)));
  return halves_[static_cast<std::size_t>(level - 1)];
}

// COARSE may be TO (the outermost call): it is read before TO is written.
void DriveStepper::refine(int level, const State& from, double t, double u, const State& coarse, State& to) {
  const auto l = static_cast<std::size_t>(level);
  const StepPlan& half = plan_at(level + 1);
  const double t_mid = t - half.dt, u_mid = 0.5 * (from.u + u);
  simulator_.step(half, from, u_mid, mid_[l], t_mid);
  simulator_.step(half, mid_[l], u, end_[l], t);
  steps_ += 2;
  const double scale = std::max({peak_, std::abs(end_[l].force), std::abs(coarse.force)});
  // The halves' error, about their difference from the one step, in the force of every node of
  // the subtree (its own force alone misses a friction element slipping at its cap while the
  // chain's other members move by different amounts): a linear subtree's result is extrapolated
  // below (second order, far within it), another's is the halves' own, so its difference is held
  // to a tenth of the tolerance.
  double difference = 0.0;
  for (const Controlled& c : controlled_) {
    double largest = 0.0;
    for (int slot : c.forces) {
      const auto i = static_cast<std::size_t>(slot);
      largest = std::max(largest, std::abs(end_[l].values[i] - coarse.values[i]));
    }
    for (int slot : c.gaps) {  // where a gap shuts next follows from its elongation now
      const auto i = static_cast<std::size_t>(slot);
      largest = std::max(largest, c.stiffness * std::abs(end_[l].values[i] - coarse.values[i]));
    }
    difference += (c.linear ? 1.0 : kUnextrapolatedWeight) * largest;
  }
  if (level + 1 == kMaxHalvings || difference <= tolerance_ * scale) {
    // A linear subtree's step is affine in its state and the drive, and the halves' error is
    // about their difference from the one step, so 2 halves - one step is second order (the
    // extrapolated implicit Euler step, L-stable); other subtrees keep the halves (a cap or a
    // stop that extrapolation could overshoot).
    State& e = end_[l];
    for (const Controlled& c : controlled_) {
      if (!c.linear) continue;
      const auto root_force = static_cast<std::size_t>(c.forces.front());
      const double before = e.values[root_force];
      for (auto i = static_cast<std::size_t>(c.first); i < static_cast<std::size_t>(c.last); ++i)
        e.values[i] = 2.0 * e.values[i] - coarse.values[i];
      e.force += e.values[root_force] - before;
    }
    to = e;
    last_from_ = &mid_[l];
    last_plan_ = &half;
    return;
  }
  refine(level + 1, from, t_mid, u_mid, mid_[l], fine_[l]);
  simulator_.step(half, fine_[l], u, coarse_[l], t);
  ++steps_;
  refine(level + 1, fine_[l], t, u, coarse_[l], to);
}

}  // namespace rheo::runtime
