// The first iterate of the global Newton solve of a subtree step (tree_newton.hpp): the last
// step's changes scaled (the secant predictor), or the split of the increment by the members'
// secant stiffnesses over it (the secant start, where the predictor's solve fails).
#include "runtime/stepping/tree_newton.hpp"

#include <algorithm>
#include <cmath>

namespace rheo::runtime {
namespace {
constexpr double kSecantSpan = 1e12;  // secant stiffnesses kept within the node's typical stiffness * 10^(+-12)
}  // namespace

void TreeNewton::start(int n, double ratio) {
  const TreeNode& t = node(n);
  const auto i = static_cast<std::size_t>(n);
  if (role(n) == NewtonRole::closed) return;
  // A block's or member's increment starts from its increment over the plan's last step, scaled
  // by the ratio of the increments (a secant predictor; 0 on a fresh plan or after a fallback).
  // A chain's force starts from its force before the step: predicted too (its change scaled),
  // it overshoots kinks (repro 06 at 0.4 mm: 24 evaluations a step and fallbacks, against 13).
  if (role(n) == NewtonRole::chain) {  // inside the forces the chain carries
    const Interval d = layout_.domain[i];
    double f = std::clamp(s_.f_before(t), d.lo, d.hi);
    // On an open end: just inside a saturation end (the force its members carry saturated in
    // double, where the last step, or the nested solve, left it), else away from a peak.
    const double away = d.lo < 0.0 && d.hi > 0.0 ? 0.0 : 0.5 * (d.lo + d.hi);
    if (f == d.hi && !layout_.reaches_hi[i]) f = layout_.saturates_hi[i] ? std::nextafter(d.hi, d.lo) : away;
    else if (f == d.lo && !layout_.reaches_lo[i]) f = layout_.saturates_lo[i] ? std::nextafter(d.lo, d.hi) : away;
    w_.x[i] = f;
  } else if (role(n) == NewtonRole::block || role(n) == NewtonRole::member) {
    w_.x[i] = ratio * w_.last[i];
  }
  for (int k = 0; k < t.child_count; ++k) start(s_.child(t, k), ratio);
}

void TreeNewton::remember(int n) {
  const TreeNode& t = node(n);
  const auto i = static_cast<std::size_t>(n);
  if (role(n) == NewtonRole::block || role(n) == NewtonRole::member) w_.last[i] = w_.x[i];
  for (int k = 0; k < t.child_count; ++k) remember(s_.child(t, k));
}

double TreeNewton::secant(int n, double de) {
  const TreeNode& t = node(n);
  const auto i = static_cast<std::size_t>(n);
  double k = 0.0;
  switch (role(n)) {
    case NewtonRole::chain: {  // compliances add; a gap counts as rigid (its play is not a stiffness)
      double compliance = 0.0;
      for (int j = 0; j < t.child_count; ++j)
        if (const int c = s_.child(t, j); node(c).kind != NodeKind::gap) compliance += 1.0 / secant(c, de);
      k = 1.0 / compliance;
      break;
    }
    case NewtonRole::sum:
    case NewtonRole::block:
      for (int j = 0; j < t.child_count; ++j) k += secant(s_.child(t, j), de);
      break;
    default: k = (s_.forward(n, de).force - s_.forward(n, 0.0).force) / de;  // a leaf, member or closed-form subtree
  }
  // Zero (a stuck slider's side, a friction element at its cap) or infinite secants would give
  // a member all or none of the increment.
  const double typical = layout_.stiffness[i];
  k = std::isfinite(k) ? std::clamp(k, typical / kSecantSpan, typical * kSecantSpan) : typical * kSecantSpan;
  w_.target[i] = k;  // scratch until the first update
  return k;
}

void TreeNewton::share(int n, double de) {
  const TreeNode& t = node(n);
  const auto i = static_cast<std::size_t>(n);
  switch (role(n)) {
    case NewtonRole::chain: {  // the members' shares of de in proportion to their secant compliances
      double compliance = 0.0;
      for (int j = 0; j < t.child_count; ++j)
        if (const int c = s_.child(t, j); node(c).kind != NodeKind::gap) compliance += 1.0 / at(w_.target, c);
      for (int j = 0; j < t.child_count; ++j)
        if (const int c = s_.child(t, j); node(c).kind != NodeKind::gap) share(c, de / (at(w_.target, c) * compliance));
      return;
    }
    case NewtonRole::block: w_.x[i] = de; [[fallthrough]];
    case NewtonRole::sum:
      for (int j = 0; j < t.child_count; ++j) share(s_.child(t, j), de);
      return;
    case NewtonRole::member: w_.x[i] = de; return;
    default: return;
  }
}

}  // namespace rheo::runtime
