#include "runtime/stepping/tree_newton.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rheo::runtime {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kRelTol = 1e-13;      // as TreeSolver's solves, relative to each residual's scale
constexpr double kFloor = 1e-9;        // absolute part of a residual's scale [mm or N]
constexpr double kTangentSpan = 1e12;  // tangents kept within stiffness * 10^(+-12) (NewtonLayout)
constexpr int kLineSearch = 6;         // halvings of a step before the watchdog takes it whole (16: repro 06 twice the work)
constexpr double kPivot = 0.9;         // share of a chain's compliance that makes a member its pivot
constexpr int kWatchdog = 4;           // full steps a solve may take that do not lower the merit
constexpr double kStagnation = 1e4;    // residuals accepted (in tolerances) where Newton no longer moves
}  // namespace

void TreeNewton::residual(double r, double scale, double rounding, bool force) {
  // Relative to the node's own scale, and no finer than the subtree's (an inner node that
  // carries next to nothing needs no digits the subtree's force cannot show).
  const double excess = std::abs(r) / (kRelTol * std::max(scale, force ? force_scale_ : length_scale_) + rounding);
  if (!(excess <= 1.0)) converged_ = false;
  worst_ = std::max(worst_, excess);
  const double q = r / (force ? force_scale_ : length_scale_);
  merit_ += q * q;
}

double TreeNewton::evaluate(int root, double de) {
  ++w_.evaluations;
  merit_ = 0.0;
  worst_ = 0.0;
  converged_ = true;
  forward(root, de);
  return merit_;
}

TreeNewton::Lin TreeNewton::forward(int n, double de) {
  at(w_.input, n) = de;
  Lin r{0.0, 0.0, 0.0};
  switch (role(n)) {
    case NewtonRole::chain: return chain(n, de);
    case NewtonRole::sum: {
      const TreeNode& t = node(n);
      for (int i = 0; i < t.child_count; ++i) {
        const Lin c = forward(s_.child(t, i), de);
        r = {r.out + c.out, r.hat + c.hat, r.tangent + c.tangent};
      }
      break;
    }
    default: {
      const ForceSlope f = s_.forward(n, de);
      r = {f.force, f.force, f.slope};
    }
  }
  at(w_.out, n) = r.out, at(w_.hat, n) = r.hat, at(w_.tangent, n) = r.tangent;
  return r;
}

TreeNewton::Lin TreeNewton::inverse(int n, double force) {
  at(w_.input, n) = force;
  if (role(n) == NewtonRole::block) return block(n, force);
  if (role(n) == NewtonRole::member) return member(n, force);
  const ForceSlope e = s_.inverse(n, force);
  at(w_.out, n) = at(w_.hat, n) = e.force, at(w_.tangent, n) = e.slope;
  return {e.force, e.force, e.slope};
}

TreeNewton::Lin TreeNewton::chain(int n, double de) {
  const TreeNode& t = node(n);
  const auto i = static_cast<std::size_t>(n);
  const double force = w_.x[i];
  state(n) = regular;
  const Interval d = layout_.domain[i];
  if (!(layout_.reaches_hi[i] ? force <= d.hi : force < d.hi) || !(layout_.reaches_lo[i] ? force >= d.lo : force > d.lo)) {
    converged_ = false, worst_ = merit_ = kInf;  // a force the chain cannot carry (rounding onto an open end)
    w_.out[i] = w_.hat[i] = force, w_.tangent[i] = 0.0;
    return {force, force, 0.0};
  }
  double sum_e = 0.0, sum_hat = 0.0, sum_c = 0.0, size = std::abs(de) + std::abs(s_.e_before(t)) + kFloor;
  double closed_c = 0.0;                // the compliance of the members whose elongation follows from F (not unknowns)
  double play_lo = 0.0, play_hi = 0.0;  // the gaps' increments to their stops
  bool gaps = false;
  for (int k = 0; k < t.child_count; ++k) {
    const int c = s_.child(t, k);
    const TreeNode& m = node(c);
    if (m.kind == NodeKind::gap) {
      const Interval stop = s_.stops(m);
      const double lo = stop.lo - s_.e_before(m), hi = stop.hi - s_.e_before(m);
      gaps = true;
      play_lo += lo, play_hi += hi;
      const double e = force > 0.0 ? hi : force < 0.0 ? lo : 0.0;
      at(w_.input, c) = force, at(w_.out, c) = at(w_.hat, c) = e, at(w_.tangent, c) = 0.0;
      sum_e += e, sum_hat += e, size += std::abs(e);
      continue;
    }
    const Lin l = inverse(c, force);
    sum_e += l.out, sum_hat += l.hat, sum_c += l.tangent, size += std::abs(l.out);
    if (role(c) == NewtonRole::closed) closed_c += l.tangent;
  }
  auto settle = [&](State s, double f) {  // a complementarity condition holds: the chain's force is f whatever de
    state(n) = s;
    w_.out[i] = w_.hat[i] = f, w_.tangent[i] = 0.0;
    residual(0.0, size, 0.0, false);
    return Lin{f, f, 0.0};
  };
  // The decisions take the members' elongations as linearised (their unknowns solved for this
  // force), which the exact ones equal once converged.
  if (gaps && force == 0.0) {
    if (de >= sum_hat + play_lo && de <= sum_hat + play_hi) return settle(play, 0.0);
    const bool up = de > sum_hat + play_hi;
    state(n) = up ? leave_up : leave_down;
    sum_e += up ? play_hi : play_lo, sum_hat += up ? play_hi : play_lo;
    for (int k = 0; k < t.child_count; ++k)
      if (const int c = s_.child(t, k); node(c).kind == NodeKind::gap) {
        const Interval stop = s_.stops(node(c));
        at(w_.out, c) = at(w_.hat, c) = (up ? stop.hi : stop.lo) - s_.e_before(node(c));
      }
  }
  const double r = sum_e - de;
  if (force == d.hi && layout_.reaches_hi[i] && sum_hat <= de) return settle(slip_hi, force);
  if (force == d.lo && layout_.reaches_lo[i] && sum_hat >= de) return settle(slip_lo, force);
  if (!(sum_c >= 0.0)) {  // a member asked for a force its law does not carry
    converged_ = false, worst_ = merit_ = kInf;
    return {force, force, 0.0};
  }
  // The rounding of F moves the elongations computed from it by C 4 eps |F|.
  residual(r, size, std::isfinite(closed_c) ? 4.0 * kEps * std::abs(force) * closed_c : 0.0, false);
  const double floor = 1.0 / (kTangentSpan * layout_.stiffness[i] + std::numeric_limits<double>::min());
  const double stiffness = 1.0 / std::clamp(sum_c, floor, kTangentSpan * kTangentSpan * floor);
  const double hat = force + (de - sum_hat) * stiffness;
  // Where the chain asks for a force beyond a softening spring's peak there is no solution
  // however small the residual's scale has become near it. Beyond a saturation end there is
  // (the saturating member elongates without bound): its residuals decide, and at a solution
  // within an ulp of the end the linearised force may round beyond it.
  if ((!layout_.reaches_hi[i] && !layout_.saturates_hi[i] && hat >= d.hi) || (!layout_.reaches_lo[i] && !layout_.saturates_lo[i] && hat <= d.lo))
    converged_ = false, worst_ = kInf;
  w_.out[i] = force, w_.hat[i] = hat, w_.tangent[i] = stiffness;
  return {force, hat, stiffness};
}

TreeNewton::Lin TreeNewton::block(int n, double force) {
  const TreeNode& t = node(n);
  const auto i = static_cast<std::size_t>(n);
  const double de = w_.x[i];
  state(n) = regular;
  const bool at_rest = t.rigid_when_stuck && de == 0.0;  // the forces of rigid members are an interval here
  double sum_f = 0.0, sum_hat = 0.0, sum_k = 0.0, size = std::abs(force) + kFloor;
  double closed_k = 0.0;  // the stiffness of the members whose force follows from de (not unknowns)
  Interval rigid{0.0, 0.0};
  for (int k = 0; k < t.child_count; ++k) {
    const int c = s_.child(t, k);
    if (at_rest && node(c).rigid_when_stuck) {
      const Interval z = s_.zero_rate_interval(c);
      rigid.lo += z.lo, rigid.hi += z.hi;
      continue;
    }
    const Lin l = forward(c, de);
    sum_f += l.out, sum_hat += l.hat, sum_k += l.tangent, size += std::abs(l.out);
    if (role(c) == NewtonRole::closed) closed_k += l.tangent;
  }
  if (de == 0.0 && layout_.kinked[i] && !at_rest) {  // on the kinks: the slopes on the side the force asks for
    sum_k = 0.0;
    for (int k = 0; k < t.child_count; ++k) {
      const int c = s_.child(t, k);
      sum_k += role(c) == NewtonRole::closed && node(c).child_count == 0 ? (at(w_.tangent, c) = s_.forward_at_rest(c, force - sum_f).slope)
                                                                         : at(w_.tangent, c);
    }
  }
  w_.load[i] = sum_f, w_.slope[i] = sum_k;
  if (at_rest) {  // decided on the linearised forces, as a chain's play
    if (force >= sum_hat + rigid.lo && force <= sum_hat + rigid.hi) {
      state(n) = stuck;
      w_.out[i] = w_.hat[i] = w_.tangent[i] = 0.0;
      residual(0.0, size, 0.0, true);
      return {0.0, 0.0, 0.0};
    }
    const bool up = force > sum_hat + rigid.hi;
    state(n) = up ? leave_up : leave_down;
    sum_f += up ? rigid.hi : rigid.lo, sum_hat += up ? rigid.hi : rigid.lo;
  }
  residual(sum_f - force, size, 4.0 * kEps * std::abs(de) * closed_k, true);
  const double floor = layout_.stiffness[i] / kTangentSpan + std::numeric_limits<double>::min();
  const double compliance = 1.0 / std::clamp(sum_k, floor, kTangentSpan * kTangentSpan * floor);
  const double hat = de + (force - sum_hat) * compliance;
  w_.out[i] = de, w_.hat[i] = hat, w_.tangent[i] = compliance;
  return {de, hat, compliance};
}

TreeNewton::Lin TreeNewton::member(int n, double force) {
  const auto i = static_cast<std::size_t>(n);
  const double de = w_.x[i];
  state(n) = regular;
  // On the kink at de = 0 the slope is taken on the side the force asks for.
  const ForceSlope f = de == 0.0 ? s_.forward_at_rest(n, force - s_.f_before(node(n))) : s_.forward(n, de);
  w_.load[i] = f.force, w_.slope[i] = f.slope;
  if (!(f.slope > 0.0) && node(n).kind != NodeKind::bouc_wen) {  // a softening spring beyond its peak
    converged_ = false, worst_ = merit_ = kInf;
    return {de, de, 0.0};
  }
  residual(f.force - force, std::abs(force) + kFloor, 4.0 * kEps * std::abs(de) * f.slope, true);
  const double floor = layout_.stiffness[i] / kTangentSpan;
  const double compliance = 1.0 / std::clamp(f.slope, floor, kTangentSpan * kTangentSpan * floor);
  const double hat = de + (force - f.force) * compliance;
  w_.out[i] = de, w_.hat[i] = hat, w_.tangent[i] = compliance;
  return {de, hat, compliance};
}

void TreeNewton::update_forward(int n, double de) {
  const TreeNode& t = node(n);
  const auto i = static_cast<std::size_t>(n);
  if (role(n) == NewtonRole::sum)
    for (int k = 0; k < t.child_count; ++k) update_forward(s_.child(t, k), de);
  if (role(n) != NewtonRole::chain) return;
  const double force = w_.x[i];
  const State st = static_cast<State>(state(n));
  const Interval d = layout_.domain[i];
  const bool kink = layout_.kinked[i];
  // The admissible force nearest to f: onto a reached cap; half way to an open end (and never
  // onto it by rounding); onto F = 0 when crossing it (a chain with gaps decides its play there;
  // a quadratic dashpot's inverse, sgn(F) sqrt(|F|/q), would have Newton alternate about it).
  auto admissible = [&](double f) {
    if (layout_.reaches_hi[i] ? f > d.hi : f >= d.hi)
      f = layout_.reaches_hi[i] ? d.hi : std::min(force + 0.5 * (d.hi - force), std::nextafter(d.hi, d.lo));
    if (layout_.reaches_lo[i] ? f < d.lo : f <= d.lo)
      f = layout_.reaches_lo[i] ? d.lo : std::max(force + 0.5 * (d.lo - force), std::nextafter(d.lo, d.hi));
    if (kink && ((force > 0.0 && f < 0.0) || (force < 0.0 && f > 0.0) || (st == leave_up && f < 0.0) || (st == leave_down && f > 0.0))) f = 0.0;
    return f;
  };
  auto update_members = [&](double f, int skip) {
    for (int k = 0; k < t.child_count; ++k)
      if (const int c = s_.child(t, k); c != skip && node(c).kind != NodeKind::gap) update_inverse(c, f);
  };
  const bool settled = st == play || st == slip_hi || st == slip_lo;
  const double linear = settled ? force : w_.hat[i] + w_.tangent[i] * (de - w_.input[i]);
  // A member or block whose compliance dominates the chain's (a bouc_wen or a block of them near
  // saturation, dF/dde -> 0) is the pivot: the linear step is solved for its elongation, which
  // stays well conditioned (in F it is 0 * inf), and the force follows its law there,
  // F = F_p(de_p), below its caps by construction. With the others linearised at the force F,
  //   de_p (1 + C_o K_p) = de - sum_o hat_o - C_o (F_p - F - K_p de_p0).
  // Where the linear step leaves through a saturation end, the member that bounds the chain
  // there is the pivot whatever its compliance: linearised on the elastic side of its kink (at
  // de_p = 0, unloading asked for) or far below saturation it would hold the chain at the end,
  // half way at a time, while it takes up the increment saturated.
  int pivot = settled ? -1 : most_compliant(n);
  if (!(pivot >= 0 && layout_.pivot[static_cast<std::size_t>(pivot)] && at(w_.tangent, pivot) * w_.tangent[i] >= kPivot))
    pivot = settled ? -1 : saturating(n, linear);
  if (pivot >= 0) {
    double others = 0.0, compliance = 0.0;
    for (int k = 0; k < t.child_count; ++k)
      if (const int c = s_.child(t, k); c != pivot) others += at(w_.hat, c), compliance += at(w_.tangent, c);
    const double k0 = at(w_.slope, pivot), x0 = at(w_.x, pivot);
    double x = (de - others - compliance * (at(w_.load, pivot) - force - k0 * x0)) / (1.0 + compliance * k0);
    const bool kinked = layout_.kinked[static_cast<std::size_t>(pivot)] || node(pivot).rigid_when_stuck;
    if (kinked && ((x0 > 0.0 && x < 0.0) || (x0 < 0.0 && x > 0.0))) x = 0.0;
    at(w_.target, pivot) = x;
    if (role(pivot) == NewtonRole::block)
      for (int k = 0; k < node(pivot).child_count; ++k) update_forward(s_.child(node(pivot), k), x);
    const double f = admissible(pivot_force(pivot, x));
    w_.target[i] = f;
    update_members(f, pivot);
    return;
  }
  w_.target[i] = admissible(linear);
  update_members(w_.target[i], -1);
}

void TreeNewton::update_inverse(int n, double force) {
  const auto i = static_cast<std::size_t>(n);
  if (role(n) == NewtonRole::member) {  // a bouc_wen stops on its kink at de = 0 when crossing it
    const double de = w_.x[i], next = w_.hat[i] + w_.tangent[i] * (force - w_.input[i]);
    w_.target[i] = layout_.kinked[i] && ((de > 0.0 && next < 0.0) || (de < 0.0 && next > 0.0)) ? 0.0 : next;
  }
  if (role(n) != NewtonRole::block) return;
  const TreeNode& t = node(n);
  const double de = w_.x[i];
  const State st = static_cast<State>(state(n));
  double next = st == stuck ? 0.0 : w_.hat[i] + w_.tangent[i] * (force - w_.input[i]);
  // Stop on de = 0 when crossing it (a block rigid while stuck decides there whether it sticks;
  // one with friction elements or bouc_wen takes their slopes on the new side there).
  if ((t.rigid_when_stuck || layout_.kinked[i]) &&
      ((de > 0.0 && next < 0.0) || (de < 0.0 && next > 0.0) || (st == leave_up && next < 0.0) || (st == leave_down && next > 0.0)))
    next = 0.0;
  w_.target[i] = next;
  for (int k = 0; k < t.child_count; ++k) update_forward(s_.child(t, k), next);
}

bool TreeNewton::advance(int root, double de, double* after, double& force) {
  ++w_.solves;
  const auto first = static_cast<std::size_t>(root);
  const double previous = w_.last_de[first];
  w_.last_de[first] = 0.0;  // a fallback leaves the next step without a predictor
  start(root, previous != 0.0 ? std::clamp(de / previous, -2.0, 2.0) : 0.0);
  bool converged = solve(root, de, after, force);
  if (!converged && de != 0.0) {  // once more from the secant start (tree_newton.hpp)
    ++w_.restarts;
    start(root, 0.0);
    secant(root, de);
    share(root, de);
    converged = solve(root, de, after, force);
  }
  if (!converged) {
    std::fill(w_.last.begin() + root, w_.last.begin() + root + layout_.extent[first], 0.0);
    return false;
  }
  remember(root);
  w_.last_de[first] = de;
  return true;
}

bool TreeNewton::solve(int root, double de, double* after, double& force) {
  // The merit's units: the force the subtree carries or takes up over the step, and the
  // elongation that force gives its stiffness.
  const double k = layout_.stiffness[static_cast<std::size_t>(root)];
  force_scale_ = std::abs(s_.f_before(node(root))) + k * std::abs(de) + std::numeric_limits<double>::min();
  length_scale_ = force_scale_ / k;
  double merit = evaluate(root, de);
  const int budget = std::min(NewtonLayout::max_iterations, cap_);
  int watchdog = 0;
  for (int iteration = 0; iteration < budget; ++iteration) {
    if (converged_) {
      assign_forward(root, de, after);
      force = at(w_.out, root);
      return true;
    }
    if (!std::isfinite(merit)) return false;
    update_forward(root, de);
    const std::size_t first = static_cast<std::size_t>(root), last = first + static_cast<std::size_t>(layout_.extent[first]);
    bool moves = false;
    for (std::size_t i = first; i < last; ++i) {
      w_.saved[i] = w_.x[i];
      if (layout_.role[i] != NewtonRole::closed && layout_.role[i] != NewtonRole::sum) {
        // Still moving: by more than rounding of the unknown, or of the subtree's scale where
        // the unknown is near 0 (a quadratic dashpot's force, whose inverse is singular there).
        const double scale = layout_.role[i] == NewtonRole::chain ? force_scale_ : length_scale_, step = std::abs(w_.target[i] - w_.x[i]);
        moves |= step > 4.0 * kEps * std::max(std::abs(w_.x[i]), scale);
        // A chain's force by less where its compliance is large (a quadratic dashpot's near
        // F = 0, Newton approaching its root there from below) still moves if it changes the
        // chain's elongations by more than stagnation accepts in its residual.
        if (layout_.role[i] == NewtonRole::chain)
          moves |= step > 4.0 * kEps * std::abs(w_.x[i]) && step > kStagnation * kRelTol * length_scale_ * w_.tangent[i];
      }
    }
    if (!moves) {  // the iterate is as good as its rounding allows (if close: else the tangents mislead)
      if (!(worst_ <= kStagnation)) return false;
      assign_forward(root, de, after);
      force = at(w_.out, root);
      return true;
    }
    double alpha = 1.0;
    for (int halving = 0;; ++halving) {
      if (halving == kLineSearch) {
        // No step along the direction lowers the merit: a tangent taken on the wrong side of a
        // kink (a friction element at its cap, a bouc_wen at a reversal, evaluated at de = 0).
        // The full step usually crosses it; a few such steps are allowed per solve.
        if (++watchdog > kWatchdog) return false;
        alpha = 1.0;
      }
      for (std::size_t i = first; i < last; ++i)
        if (layout_.role[i] != NewtonRole::closed && layout_.role[i] != NewtonRole::sum)
          w_.x[i] = alpha == 1.0 ? w_.target[i] : w_.saved[i] + alpha * (w_.target[i] - w_.saved[i]);
      const double trial = evaluate(root, de);
      if (converged_ || trial <= (1.0 - 1e-4 * alpha) * merit || halving == kLineSearch) {
        merit = trial;
        break;
      }
      alpha *= 0.5;
    }
  }
  if (!converged_) return false;
  assign_forward(root, de, after);
  force = at(w_.out, root);
  return true;
}

}  // namespace rheo::runtime
