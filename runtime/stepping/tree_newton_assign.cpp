// Writing a converged step of the global Newton solve into the states, and the members of a
// chain that take its rounding remainder or pivot its step (tree_newton.hpp).
#include "runtime/stepping/tree_newton.hpp"

#include <algorithm>

namespace rheo::runtime {

void TreeNewton::assign_forward(int n, double de, double* after) {
  const TreeNode& t = node(n);
  switch (role(n)) {
    case NewtonRole::chain: assign_chain(n, de, after); return;
    case NewtonRole::sum:
      after[t.state] = s_.e_before(t) + de;
      after[t.state + 1] = at(w_.out, n);
      if (t.rigid_when_stuck && de == 0.0) assign_stuck(n, at(w_.out, n), after);
      else
        for (int k = 0; k < t.child_count; ++k) assign_forward(s_.child(t, k), de, after);
      return;
    default: s_.assign(n, de, de == at(w_.input, n) ? at(w_.out, n) : s_.forward(n, de).force, after);
  }
}

void TreeNewton::assign_inverse(int n, double e, double force, double* after) {
  const TreeNode& t = node(n);
  if (role(n) == NewtonRole::member) {  // its state follows its own law exactly: its force at e
    s_.assign(n, e, e == at(w_.x, n) ? at(w_.load, n) : s_.forward(n, e).force, after);
    return;
  }
  if (role(n) != NewtonRole::block) {
    s_.assign(n, e, force, after);
    return;
  }
  after[t.state] = s_.e_before(t) + e;
  after[t.state + 1] = force;
  if (t.rigid_when_stuck && e == 0.0 && at(w_.x, n) == 0.0) assign_stuck(n, force, after);
  else
    for (int k = 0; k < t.child_count; ++k) assign_forward(s_.child(t, k), e, after);
}

// A block at de = 0 rigid while stuck (TreeSolver::assign_parallel): the compliant members
// carry their forces at zero increment, the rigid ones what is left within their intervals.
void TreeNewton::assign_stuck(int n, double force, double* after) {
  const TreeNode& t = node(n);
  double remainder = force;
  for (int k = 0; k < t.child_count; ++k)
    if (const int c = s_.child(t, k); !node(c).rigid_when_stuck) remainder -= at(w_.out, c);
  int last_rigid = -1;
  for (int k = 0; k < t.child_count; ++k) {
    const int c = s_.child(t, k);
    if (!node(c).rigid_when_stuck) {
      assign_forward(c, 0.0, after);
      continue;
    }
    last_rigid = c;
    const Interval z = s_.zero_rate_interval(c);
    const double share = std::clamp(remainder, z.lo, z.hi);
    s_.assign(c, 0.0, share, after);
    remainder -= share;
  }
  if (remainder != 0.0 && last_rigid >= 0) after[node(last_rigid).state + 1] += remainder;
}

void TreeNewton::assign_chain(int n, double de, double* after) {
  const TreeNode& t = node(n);
  const double force = at(w_.x, n);
  after[t.state] = s_.e_before(t) + de;
  after[t.state + 1] = force;
  if (state(n) == play) {  // F = 0: the members at their zero-force elongations, the gaps share the rest in order
    double rest = de;
    int last_gap = -1;
    for (int k = 0; k < t.child_count; ++k)
      if (const int c = s_.child(t, k); node(c).kind != NodeKind::gap) rest -= at(w_.out, c);
      else last_gap = c;
    for (int k = 0; k < t.child_count; ++k) {
      const int c = s_.child(t, k);
      const TreeNode& m = node(c);
      if (m.kind != NodeKind::gap) {
        assign_inverse(c, at(w_.out, c), 0.0, after);
        continue;
      }
      const Interval stop = s_.stops(m);
      const double share = c == last_gap ? rest : std::clamp(rest, stop.lo - s_.e_before(m), stop.hi - s_.e_before(m));
      after[m.state] = s_.e_before(m) + share;
      after[m.state + 1] = 0.0;
      rest -= share;
    }
    return;
  }
  // The rounding remainder goes to the member that slips at the cap, else to the most compliant.
  int taker = -1;
  if (state(n) == slip_hi || state(n) == slip_lo)
    for (int k = 0; k < t.child_count && taker < 0; ++k)
      if (const Interval b = s_.bounds(s_.child(t, k)); force >= b.hi || force <= b.lo) taker = s_.child(t, k);
  if (taker < 0) taker = most_compliant(n);
  double taken = 0.0;
  for (int k = 0; k < t.child_count; ++k) {
    const int c = s_.child(t, k);
    if (c == taker) continue;
    taken += at(w_.out, c);
    assign_inverse(c, at(w_.out, c), force, after);
  }
  if (taker >= 0) assign_inverse(taker, de - taken, force, after);
}

double TreeNewton::pivot_force(int n, double de) const {
  if (role(n) == NewtonRole::member) return s_.forward(n, de).force;
  const TreeNode& t = node(n);
  double f = 0.0;  // closed members by their laws, chains as linearised
  for (int k = 0; k < t.child_count; ++k) {
    const int c = s_.child(t, k);
    f += role(c) == NewtonRole::closed ? s_.forward(c, de).force : at(w_.hat, c) + at(w_.tangent, c) * (de - at(w_.input, c));
  }
  return f;
}

int TreeNewton::saturating(int n, double force) const {
  const TreeNode& t = node(n);
  const auto i = static_cast<std::size_t>(n);
  const Interval d = layout_.domain[i];
  const bool hi = layout_.saturates_hi[i] && force >= d.hi, lo = layout_.saturates_lo[i] && force <= d.lo;
  for (int k = 0; k < t.child_count && (hi || lo); ++k)
    if (const int c = s_.child(t, k); layout_.pivot[static_cast<std::size_t>(c)] && (hi ? s_.bounds(c).hi == d.hi : s_.bounds(c).lo == d.lo))
      return c;
  return -1;
}

int TreeNewton::most_compliant(int n) const {
  const TreeNode& t = node(n);
  int taker = -1;
  double most = -1.0;
  for (int k = 0; k < t.child_count; ++k)
    if (const int c = s_.child(t, k); node(c).kind != NodeKind::gap && w_.tangent[static_cast<std::size_t>(c)] >= most)
      most = w_.tangent[static_cast<std::size_t>(c)], taker = c;
  return taker;
}

}  // namespace rheo::runtime
