// PwlPeriodicState::Run::replay (pwl_cycle.hpp): the span's map along a recorded sequence of
// switches, for the shooting's Newton iterations between followed cycles (pwl_periodic.cpp).
#include "runtime/closed_form/pwl_cycle.hpp"

#include <cmath>

namespace rheo::runtime {

bool PwlPeriodicState::Run::replay(const PwlVector& X0, PwlVector& X_T, PwlMatrix& J) {
  const std::vector<Piece>& pieces = self.pieces_;
  if (pieces.empty() || self.fired_.size() + 1 != pieces.size()) return false;
  int m = pieces.front().mode;
  PwlVector w = self.system(m).state_at(X0, 0.0, self.u0_), next;
  PwlMatrix S = self.system(m).from_X;
  S.bottomRows(3).setZero();
  const double converged = 1e-14 * step;  // the switch time's last Newton step [s]
  double t = 0.0;
  for (std::size_t k = 1; k < pieces.size(); ++k) {
    const PwlModeSystem& s = self.system(m);
    const int i = self.fired_[k - 1];
    const auto G = s.guards.row(i), dG = s.guard_rates.row(i);
    // Newton's method on g(tau) = G w(tau) from the recorded switch time: the guard falls
    // through zero there (a crossing, not a touch), each iterate nudged from the last.
    double tau = pieces[k].t - t;
    if (tau > 0.0) {
      PwlVector w_tau = s.advance(tau, w);
      for (int it = 0;; ++it) {
        const double g = G.dot(w_tau), dg = dG.dot(w_tau);
        if (!(dg < 0.0) || it == 8) return false;
        const double delta = -g / dg;
        if (!s.nudge(delta, w_tau, next)) next = s.advance(tau + delta, w);
        w_tau.swap(next);
        tau += delta;
        if (std::abs(delta) <= converged) break;
      }
      // A switch at the piece's start (the cycle's "now": its guard already at zero there)
      // lands a rounding error either side of it.
      if (tau < 0.0 && tau > -1e-12 * step) tau = 0.0;
      if (!(tau >= 0.0 && t + tau < self.span_)) return false;
      s.propagate(tau, S);
      w.swap(w_tau);
      t += tau;
    }
    m = switch_at(m, i, w, &S, pieces[k].mode);
  }
  const PwlModeSystem& s = self.system(m);
  const double rest = self.span_ - t;
  w = s.advance(rest, w);
  s.propagate(rest, S);
  X_T = s.to_X.lazyProduct(w);
  multiply(s.to_X, S, J);
  return true;
}

}  // namespace rheo::runtime
