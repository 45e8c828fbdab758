#include "runtime/stepping/jump_hold.hpp"

#include "runtime/stepping/tree_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rheo::runtime {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Calls F(node) for NODE and every node below it.
template <class F>
void for_each_below(const Topology& t, int node, F&& f) {
  f(node);
  const TreeNode& n = t.nodes[static_cast<std::size_t>(node)];
  for (int i = 0; i < n.child_count; ++i) for_each_below(t, t.children[static_cast<std::size_t>(n.first_child + i)], f);
}

double dot(const double* a, const double* b, std::size_t n) {
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) sum += a[i] * b[i];
  return sum;
}

}  // namespace

bool JumpHoldStep::applies(const Topology& topology) {
  for (int root : topology.subtrees) {
    const TreeNode& r = topology.nodes[static_cast<std::size_t>(root)];
    if (!r.linear && !(r.capped_linear && !r.rigid_when_stuck)) return false;
    bool prescribed = false;
    for_each_below(topology, root, [&](int n) { prescribed |= topology.nodes[static_cast<std::size_t>(n)].drive_prescribed; });
    if (prescribed) return false;
  }
  return true;
}

JumpHoldStep::JumpHoldStep(const Network& network, double dt, double delta) {
  if (!applies(network.topology())) throw std::logic_error("JumpHoldStep: a subtree is not piecewise affine");
  if (!(delta > 0.0 && delta < dt)) throw std::logic_error("JumpHoldStep: the ramp must be a part of the step");
  const StepPlan jump = StepPlan::make(network, delta), hold = StepPlan::make(network, dt - delta);
  root_.dt = dt;
  for (std::size_t i = 0; i < jump.maxwell_a.size(); ++i) {
    root_.maxwell_a.push_back(hold.maxwell_a[i] * jump.maxwell_a[i]);
    root_.maxwell_b.push_back(hold.maxwell_a[i] * jump.maxwell_b[i]);
  }
  root_.dashpot_c_over_dt = 0.0;
  std::size_t widest = 0;
  for (int root : network.topology().subtrees) {
    subtrees_.push_back(make_subtree(network, root, dt, delta));
    widest = std::max(widest, subtrees_.back().live.size() + 2);
  }
  inputs_.assign(widest, 0.0);
}

JumpHoldStep::Subtree JumpHoldStep::make_subtree(const Network& network, int root, double dt, double delta) const {
  const Topology& t = network.topology();
  Subtree s;
  int lo = t.state_size, hi = 0, slots = 0;
  std::vector<char> is_elongation(static_cast<std::size_t>(t.state_size), 0);
  for_each_below(t, root, [&](int node) {
    const TreeNode& n = t.nodes[static_cast<std::size_t>(node)];
    lo = std::min(lo, n.state);
    hi = std::max(hi, n.state + n.slots);
    slots += n.slots;
    is_elongation[static_cast<std::size_t>(n.state)] = 1;  // (e, F, ...): e first
  });
  if (hi - lo != slots) throw std::logic_error("JumpHoldStep: a subtree's state slots are not contiguous");
  s.first = lo;
  s.count = slots;
  const TreeNode& r = t.nodes[static_cast<std::size_t>(root)];
  s.force_slot = r.state + 1;
  const auto count = static_cast<std::size_t>(s.count);

  StepPlan jump = StepPlan::make(network, delta), hold = StepPlan::make(network, dt - delta);
  // The closed forms, affine on any state within a mode.
  jump.tree.global_newton = hold.tree.global_newton = false;
  jump.tree.clamp_friction = hold.tree.clamp_friction = false;
  const Interval cap = r.capped_linear ? jump.tree.bounds[static_cast<std::size_t>(root)] : Interval{-kInf, kInf};
  s.cap_lo = cap.lo;
  s.cap_hi = cap.hi;
  const auto forced = [&](int mode) {
    return mode == upper ? Interval{cap.hi, cap.hi} : mode == lower ? Interval{cap.lo, cap.lo} : Interval{-kInf, kInf};
  };
  const auto reachable = [&](int mode) { return mode == free || std::isfinite(mode == upper ? cap.hi : cap.lo); };

  // raw[3 m1 + m2][column]: the range's slots after both parts, then the force of each part,
  // for a unit state in slot `column` of the range (column count: J = 1; count + 1: all zero).
  const std::size_t columns = count + 2;
  std::vector<std::vector<std::vector<double>>> raw(9);
  std::vector<double> before(static_cast<std::size_t>(t.state_size)), mid(before.size()), after(before.size());
  for (int m1 = 0; m1 < 3; ++m1) {
    if (!reachable(m1)) continue;
    jump.tree.bounds[static_cast<std::size_t>(root)] = forced(m1);
    for (int m2 = 0; m2 < 3; ++m2) {
      if (!reachable(m2)) continue;
      hold.tree.bounds[static_cast<std::size_t>(root)] = forced(m2);
      auto& out = raw[static_cast<std::size_t>(3 * m1 + m2)];
      out.assign(columns, std::vector<double>(count + 2));
      for (std::size_t column = 0; column < columns; ++column) {
        std::fill(before.begin(), before.end(), 0.0);
        std::fill(mid.begin(), mid.end(), kNaN);
        std::fill(after.begin(), after.end(), kNaN);
        if (column < count) before[static_cast<std::size_t>(s.first) + column] = 1.0;
        const double jump_size = column == count ? 1.0 : 0.0;
        const double f1 = TreeSolver(network, jump.tree, before.data(), kNaN).advance(root, jump_size, mid.data());
        const double f2 = TreeSolver(network, hold.tree, mid.data(), kNaN).advance(root, 0.0, after.data());
        std::copy_n(after.begin() + s.first, count, out[column].begin());
        out[column][count] = f1;
        out[column][count + 1] = f2;
        if (std::any_of(out[column].begin(), out[column].end(), [](double v) { return !std::isfinite(v); }))
          throw std::logic_error("JumpHoldStep: a subtree step left a slot unwritten or not finite");
      }
    }
  }

  // A slot is live when some mode's result moves with it, other than its own elongation's
  // carrying over (which E does).
  const std::size_t constant = count + 1;
  for (std::size_t column = 0; column < count; ++column) {
    bool live = false;
    for (const auto& out : raw)
      for (std::size_t row = 0; row < count + 2 && !out.empty(); ++row)
        live |= out[column][row] != out[constant][row] && !(row == column && is_elongation[static_cast<std::size_t>(s.first) + column]);
    if (live) s.live.push_back(s.first + static_cast<int>(column));
  }
  s.elongation.resize(count);
  for (std::size_t i = 0; i < count; ++i) s.elongation[i] = is_elongation[static_cast<std::size_t>(s.first) + i] ? 1.0 : 0.0;

  // Coefficients of [x_live, J, 1] for ROW of mode pair PAIR (row count: the ramp's force,
  // count + 1: the hold's).
  const auto coefficients = [&](std::size_t pair, std::size_t row, std::vector<double>& into) {
    const auto& out = raw[pair];
    for (int slot : s.live) {
      const auto column = static_cast<std::size_t>(slot - s.first);
      into.push_back(out[column][row] - out[constant][row] - (row == column && s.elongation[row] != 0.0 ? 1.0 : 0.0));
    }
    into.push_back(out[count][row] - out[constant][row]);
    into.push_back(out[constant][row]);
  };
  for (std::size_t pair = 0; pair < 9; ++pair) {
    if (raw[pair].empty()) continue;
    for (std::size_t row = 0; row < count; ++row) coefficients(pair, row, s.map[pair]);
    if (pair % 3 == free) coefficients(pair, count + 1, s.trial_after[pair / 3]);
  }
  coefficients(3 * free + free, count, s.trial);
  return s;
}

double JumpHoldStep::advance(const Subtree& s, const double* before, double jump, double* after) const {
  const std::size_t live = s.live.size(), width = live + 2;
  double* in = inputs_.data();
  for (std::size_t j = 0; j < live; ++j) in[j] = before[s.live[j]];
  in[live] = jump;
  in[live + 1] = 1.0;
  std::size_t pair = 0;
  if (std::isfinite(s.cap_lo) || std::isfinite(s.cap_hi)) {
    const double t1 = dot(s.trial.data(), in, width);
    const int m1 = t1 >= s.cap_hi ? upper : t1 <= s.cap_lo ? lower : free;
    const double t2 = dot(s.trial_after[static_cast<std::size_t>(m1)].data(), in, width);
    pair = static_cast<std::size_t>(3 * m1 + (t2 >= s.cap_hi ? upper : t2 <= s.cap_lo ? lower : free));
  }
  const double* m = s.map[pair].data();
  const double* x = before + s.first;
  double* y = after + s.first;
  for (std::size_t i = 0; i < static_cast<std::size_t>(s.count); ++i) y[i] = s.elongation[i] * x[i] + dot(m + i * width, in, width);
  return after[s.force_slot];
}

double JumpHoldStep::step(const Simulator& simulator, const State& before, double u_next, State& after) const {
  double force = simulator.step_root(root_, before, u_next, after);
  const double jump = u_next - before.u;
  for (const Subtree& s : subtrees_) force += advance(s, before.values.data(), jump, after.values.data());
  after.u = u_next;
  after.force = force;
  return force;
}

}  // namespace rheo::runtime
