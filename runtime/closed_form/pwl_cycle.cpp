#include "runtime/closed_form/pwl_cycle.hpp"

#include "runtime/closed_form/pwl_fixed_point.hpp"

#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <utility>

namespace rheo::runtime {
namespace {

using Complex = std::complex<double>;

constexpr int kMaxSwitchesPerCycle = 10000;
constexpr double kGuardTolerance = 1e-10;  // relative to each guard's scale

// Whether a guard with value g, slope dg and curvature ddg is being left now: below zero
// beyond the tolerance, or on zero (within tol) and moving down (beyond dtol), or on zero and
// level and curving down (a switch where the slopes of both modes vanish, as when a slipping
// slider's rate reaches zero exactly as its stuck force would reach the cap).
bool leaving(double g, double dg, double ddg, double tol, double dtol) {
  if (g < -tol) return true;
  if (g > tol) return false;
  return dg < -dtol || (dg <= dtol && ddg < 0.0);
}

using Stacked = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3 * kPwlMaxDim + 1, 1>;

}  // namespace

int PwlPeriodicState::Run::mode_index(const PwlModeCode& code) {
  for (int i : self.active_)
    if (self.system(i).code == code) return i;
  PwlModeStructure* structure = nullptr;
  for (std::size_t k = 0; k < self.structure_count_ && structure == nullptr; ++k)
    if (self.structures_[k].first == code) structure = &self.structures_[k].second;
  if (structure == nullptr) {
    if (self.structure_count_ == self.structures_.size()) self.structures_.emplace_back();
    auto& [known, st] = self.structures_[self.structure_count_++];
    known = code, st.filled = false, st.determinate = true;
    structure = &st;
  }
  // Built in place, over a mode of an earlier solve where there is one: a mode's
  // fixed-capacity storage is tens of kilobytes, not to be allocated and cleared per point.
  if (self.mode_count_ == self.modes_.size()) {
    self.modes_.emplace_back(), self.grid_step_.emplace_back(), self.mode_omega_.emplace_back(), self.linear_start_.emplace_back();
    self.systems_.push_back(&self.modes_.back());
  }
  if (!build_pwl_mode(branch, code, self.omega_, self.modes_[self.mode_count_], structure)) return -1;
  self.grid_step_[self.mode_count_].resize(0, 0);
  self.linear_start_[self.mode_count_].resize(0);
  self.mode_omega_[self.mode_count_] = self.omega_;
  self.active_.push_back(static_cast<int>(self.mode_count_));
  return static_cast<int>(self.mode_count_++);
}

const PwlPeriodicState::PwlGridStep& PwlPeriodicState::Run::grid_step(int m) {
  PwlGridStep& stacked = self.grid_step_[static_cast<std::size_t>(m)];
  if (stacked.size() == 0) {
    const PwlModeSystem& s = self.system(m);
    const PwlMatrix E = s.propagator(step);
    stacked.resize(s.dim + 2 * s.guards.rows() + 1, s.dim);
    stacked << E, s.guards * E, s.guard_rates * E, s.force_rate * E;
  }
  return stacked;
}

bool PwlPeriodicState::Run::leaves(int m, int i, const PwlVector& w) {
  const PwlModeSystem& s = self.system(m);
  const double tol = kGuardTolerance * s.transitions[static_cast<std::size_t>(i)].size(self.u0_);
  const PwlRow G = s.guards.row(i);
  const double g = G.dot(w);
  if (g > tol) return false;
  const double probe = 1e-7 * self.period_;
  PwlVector rate, rate_of_rate;
  multiply(s.A, w, rate);
  multiply(s.A, rate, rate_of_rate);
  const double slope = G.dot(rate), curvature = G.dot(rate_of_rate);
  const bool turning = g >= -tol && slope < 0.0 && slope + curvature * probe > 0.0;
  if (!turning && leaving(g, slope, curvature, tol, tol * self.omega_)) return true;
  PwlVector& ahead = self.probe_;
  if (!s.nudge(probe, w, ahead)) ahead = s.advance(probe, w);
  return G.dot(ahead) < -tol;
}

int PwlPeriodicState::Run::settle(int m, const PwlVector& X, double s_drive, double c_drive, PwlVector& w) {
  for (int attempt = 0; attempt <= 2 * static_cast<int>(branch.switches.size()) + 2; ++attempt) {
    if (m < 0) return -1;
    const PwlModeSystem& s = self.system(m);
    w = s.state_at(X, s_drive, c_drive);
    int violated = -1;
    for (int i = 0; i < s.guards.rows() && violated < 0; ++i)
      if (leaves(m, static_cast<int>(i), w)) violated = static_cast<int>(i);
    if (violated < 0) return m;
    PwlModeCode& code = self.settle_code_;
    code = s.code;
    const PwlTransition& tr = s.transitions[static_cast<std::size_t>(violated)];
    code[static_cast<std::size_t>(tr.which)] = tr.to;
    m = mode_index(code);
  }
  return -1;
}

double PwlPeriodicState::Run::first_crossing(int m, int i, const PwlVector& w0, const PwlVector& w1, double h, double g0, double g1, double slope0,
                                             double slope1, PwlVector& w_at) {
  const PwlModeSystem& s = self.system(m);
  const auto G = s.guards.row(i), dG = s.guard_rates.row(i);
  const double tol = kGuardTolerance * s.transitions[static_cast<std::size_t>(i)].size(self.u0_);
  constexpr double never = std::numeric_limits<double>::infinity();
  // The state at tau into the step: nudged from the last state found (or from the step's end)
  // where that is near enough (PwlModeSystem::nudge), else the flow from w0.
  double known_t = 0.0;
  const PwlVector* known = &w0;  // the state at known_t: w0, then w_at (nudged in place)
  auto at = [&](double tau) -> const PwlVector& {
    const bool from_end = std::abs(tau - h) < std::abs(tau - known_t);
    if (!s.nudge(from_end ? tau - h : tau - known_t, from_end ? w1 : *known, w_at)) w_at = s.advance(tau, w0);
    known_t = tau, known = &w_at;
    return w_at;
  };
  // The cubic through the values and slopes at both ends, c(x) = ((a3 x + a2) x + a1) x + g0
  // for tau = x h: within O(h^4) of the guard over a step of T/64, so it bounds a dip closely
  // and its root starts Newton's method a few digits from the crossing.
  const double a3 = 2.0 * (g0 - g1) + h * (slope0 + slope1), a2 = 3.0 * (g1 - g0) - h * (2.0 * slope0 + slope1), a1 = h * slope0;
  auto cubic = [&](double x) { return ((a3 * x + a2) * x + a1) * x + g0; };
  double lo = 0.0, hi = h, g_lo = g0, g_hi = g1;  // the guard is positive at lo, not at hi
  if (g1 >= 0.0) {
    // Both ends non-negative: a dip below zero needs the slope negative at 0 and positive at h;
    // only a dip the cubic brings within a tenth of the smaller end value is located.
    if (!(slope0 < 0.0 && slope1 > 0.0)) return never;
    double lowest = std::min(g0, g1), x_lowest = 0.5;
    const double disc = a2 * a2 - 3.0 * a3 * a1;
    if (disc >= 0.0 && a3 != 0.0)
      for (double x : {(-a2 + std::sqrt(disc)) / (3.0 * a3), (-a2 - std::sqrt(disc)) / (3.0 * a3)})
        if (x > 0.0 && x < 1.0 && cubic(x) < lowest) lowest = cubic(x), x_lowest = x;
    if (lowest > 0.1 * std::min(g0, g1)) return never;
    // The minimum: the slope's root, by safeguarded Newton (curvature ddG w) from the cubic's.
    const PwlRow ddG = dG * s.A;
    double a = 0.0, b = h, tau = x_lowest * h;
    for (int it = 0; it < 60 && b - a > 1e-14 * h; ++it) {
      const PwlVector& w = at(tau);
      const double slope = dG.dot(w), curvature = ddG.dot(w);
      (slope < 0.0 ? a : b) = tau;
      double next = curvature > 0.0 ? tau - slope / curvature : 0.5 * (a + b);
      if (!(next > a && next < b)) next = 0.5 * (a + b);
      if (std::abs(next - tau) <= 1e-14 * h) break;
      tau = next;
    }
    // The last iterate is the minimum where Newton converged from one side; b where the
    // bracket closed from both.
    if (const double v = G.dot(at(tau)); v < 0.0) hi = tau, g_hi = v;
    else if (const double v_b = G.dot(at(b)); v_b < 0.0) hi = b, g_hi = v_b;
    else return never;
  }
  if (g0 <= tol && leaves(m, i, w0)) {
    w_at = w0;
    return 0.0;  // the switch is now
  }
  double tau = std::numeric_limits<double>::quiet_NaN();
  if (g0 <= tol) {
    // On the guard and not leaving it (the mode was just entered): find a point where it is
    // positive before a crossing; a sample below zero first brackets the crossing itself.
    bool found = false;
    for (int j = 0; j < 16 && !found; ++j) {
      const double sample = j == 0 ? std::min(hi, 1e-7 * self.period_) : hi * j / 16.0;
      const double v = G.dot(at(sample));
      if (v > tol) lo = sample, g_lo = v, found = true;
      else if (v < -tol) hi = sample, g_hi = v, found = true;
    }
    if (!found) return never;
  } else {
    // The cubic's root in the bracket, by Newton's method safeguarded by bisection (the cubic
    // is positive at lo, negative at hi), from the chord's root.
    double a = lo / h, b = hi / h;
    const double ca = cubic(a), cb = cubic(b);
    if (ca > 0.0 && cb < 0.0) {
      double x = a + (b - a) * ca / (ca - cb);
      for (int it = 0; it < 60 && b - a > 1e-13; ++it) {
        const double c = cubic(x), dc = (3.0 * a3 * x + 2.0 * a2) * x + a1;
        (c > 0.0 ? a : b) = x;
        double next = dc != 0.0 ? x - c / dc : 0.5 * (a + b);
        // Converged before the safeguard: Newton's last step may land on the bracket's end that
        // x just became (c = 0 at the root), where a bisection would crawl to the same point.
        if (std::abs(next - x) <= 1e-13) {
          x = next;
          break;
        }
        if (!(next > a && next < b)) next = 0.5 * (a + b);
        if (std::abs(next - x) <= 1e-13) {
          x = next;
          break;
        }
        x = next;
      }
      tau = x * h;
    }
  }
  // Newton's method safeguarded by the bracket [lo, hi] with g(lo) > 0 >= g(hi): a step that
  // leaves it takes the chord's root instead (the crossing often lies at a bracket's end, a
  // grid point such as the drive's turning point, where bisection would crawl; it is hi itself
  // where the guard is 0 there), and where that is not inside either, the midpoint.
  if (!(tau > lo && tau < hi)) tau = 0.5 * (lo + hi);
  for (int it = 0; it < 100; ++it) {
    const PwlVector& w = at(tau);
    const double g = G.dot(w), dg = dG.dot(w);
    if (g > 0.0) lo = tau, g_lo = g;
    else hi = tau, g_hi = g;
    double next = dg != 0.0 ? tau - g / dg : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) {
      if (g_hi == 0.0) {  // hi is the crossing
        at(hi);
        return hi;
      }
      next = lo + (hi - lo) * (g_lo / (g_lo - g_hi));
    }
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - tau) <= 1e-15 * self.period_) {
      if (next > tau) at(next);
      return std::max(tau, next);
    }
    if (hi - lo <= 1e-15 * self.period_) {
      at(hi);
      return hi;
    }
    tau = next;
  }
  at(hi);
  return hi;
}

int PwlPeriodicState::Run::switch_at(int m, int i, PwlVector& w, PwlMatrix* S, int to) {
  const PwlModeSystem& old = self.system(m);
  PwlVector X;
  multiply(old.to_X, w, X);
  const double s_drive = w[old.sine()], c_drive = w[old.cosine()];  // u0 sin(w t), u0 cos(w t)
  PwlVector w_new;
  int next = to;
  if (to >= 0) {
    w_new = self.system(to).state_at(X, s_drive, c_drive);
  } else {
    PwlModeCode& code = self.switch_code_;
    code = old.code;
    const PwlTransition& tr = old.transitions[static_cast<std::size_t>(i)];
    code[static_cast<std::size_t>(tr.which)] = tr.to;
    next = settle(mode_index(code), X, s_drive, c_drive, w_new);
    if (next < 0) return -1;
  }
  if (S != nullptr) {
    const PwlModeSystem& o = self.system(m);
    const PwlModeSystem& n = self.system(next);
    PwlVector rate_old, drift;
    multiply(o.A, w, rate_old);
    const double slope = o.guards.row(i).dot(rate_old);
    const Eigen::Index columns = S->cols();
    std::array<double, kPwlMaxDim> dt{};  // dt/dX0 of the switch time
    if (std::abs(slope) > 1e-300)
      for (Eigen::Index c = 0; c < columns; ++c) dt[static_cast<std::size_t>(c)] = -o.guards.row(i).dot(S->col(c)) / slope;
    multiply(n.A, w_new, drift);
    drift = -drift;
    drift.segment(n.nz, n.nh) += n.held_drive * (self.omega_ * c_drive);
    // S_new = from_X_new (to_X_old (S + rate_old dt)) + drift dt.
    for (Eigen::Index c = 0; c < columns; ++c) S->col(c) += rate_old * dt[static_cast<std::size_t>(c)];
    PwlMatrix positions;
    multiply(o.to_X, *S, positions);
    multiply(n.from_X, positions, *S);
    for (Eigen::Index c = 0; c < columns; ++c) S->col(c) += drift * dt[static_cast<std::size_t>(c)];
    S->bottomRows(3).setZero();
  }
  w = std::move(w_new);
  return next;
}

bool PwlPeriodicState::Run::cycle(int& m, const PwlVector& X0, PwlVector& X_T, PwlMatrix* J, bool record) {
  // The state w (dim entries), the guards (g), their slopes (g') and dF/dt at both ends of a
  // step, stacked [w; g; g'; dF/dt] as the grid step's product gives them: the start's and the
  // end's, exchanged by pointer where a step ends without an event (no copies per step). The
  // state is copied out where a guard may cross within the step, or after a switch.
  Stacked ends[2];
  Stacked *at_start = &ends[0], *at_end = &ends[1];
  PwlVector w, w1;  // the state at the step's start and end, where copied out
  m = settle(m, X0, 0.0, self.u0_, w);
  if (m < 0) return false;
  PwlMatrix S;
  PwlMatrix* Sp = nullptr;
  if (J != nullptr) {
    S = self.system(m).from_X;
    S.bottomRows(3).setZero();
    Sp = &S;
  }
  const int grid_steps = self.half_wave_ ? kPwlGridPerCycle / 2 : kPwlGridPerCycle;
  // [w; G w; G' w; F' w] of mode m into OUT.
  auto stack = [&](const PwlVector& state, Stacked& out) {
    const PwlModeSystem& s = self.system(m);
    const Eigen::Index dim = s.dim, guards = s.guards.rows();
    out.resize(dim + 2 * guards + 1);
    out.head(dim) = state;
    out.segment(dim, guards).noalias() = s.guards.lazyProduct(state);
    out.segment(dim + guards, guards).noalias() = s.guard_rates.lazyProduct(state);
    out[dim + 2 * guards] = s.force_rate.dot(state);
  };
  auto grid_slope = [&] { return (*at_start)[at_start->size() - 1]; };
  stack(w, *at_start);
  if (record) {
    self.pieces_.assign(1, {0.0, m, w}), self.switch_phases_.clear(), self.fired_.clear();
    self.grid_slopes_.resize(static_cast<std::size_t>(grid_steps) + 1);
    self.grid_slopes_[0] = grid_slope();
  }
  int switches = 0;
  double t = 0.0, piece_start = 0.0;
  PwlVector w_cross, w_first;  // the state at a guard's crossing, and at the first one's
  // grid_step(m) once a full step needs it, looked up again after a switch (building a mode
  // may move the storage).
  const PwlGridStep* E = nullptr;
  for (int k = 0; k < grid_steps; ++k) {
    const double t_end = k + 1 == grid_steps ? self.span_ : (k + 1) * step;
    while (t < t_end) {
      const PwlModeSystem& s = self.system(m);
      const double h = t_end - t;
      const bool full = std::abs(h - step) <= 1e-12 * step;
      const Eigen::Index dim = s.dim, guards = s.guards.rows();
      bool copied = false;  // w, w1 hold the step's ends
      if (full) {
        if (E == nullptr) E = &grid_step(m);
        multiply(*E, *at_start, *at_end);
      } else {
        w = at_start->head(dim);
        w1 = advance(m, h, w);
        stack(w1, *at_end);
        copied = true;
      }
      const auto g0 = at_start->segment(dim, guards), g1 = at_end->segment(dim, guards);
      const auto dg0 = at_start->segment(dim + guards, guards), dg1 = at_end->segment(dim + guards, guards);
      double first = std::numeric_limits<double>::infinity();
      int fired = -1;
      for (Eigen::Index i = 0; i < guards; ++i) {
        if (g1[i] >= 0.0 && !(dg0[i] < 0.0 && dg1[i] > 0.0)) continue;  // no crossing and no dip
        if (!copied) w = at_start->head(dim), w1 = at_end->head(dim), copied = true;
        const double tau = first_crossing(m, static_cast<int>(i), w, w1, h, g0[i], g1[i], dg0[i], dg1[i], w_cross);
        if (tau < first) first = tau, fired = static_cast<int>(i), w_first = w_cross;
      }
      if (fired < 0) {
        std::swap(at_start, at_end);
        t = t_end;
        break;
      }
      w = w_first;
      t += first;
      if (Sp != nullptr) s.propagate(t - piece_start, *Sp), piece_start = t;
      if (++switches > kMaxSwitchesPerCycle) return false;
      m = switch_at(m, fired, w, Sp);
      if (m < 0) return false;
      E = nullptr;
      stack(w, *at_start);
      if (record) {
        self.fired_.push_back(fired);
        self.pieces_.push_back({t, m, w});
        self.switch_phases_.push_back(std::fmod(self.omega_ * t, 2.0 * std::numbers::pi));
      }
    }
    if (record) self.grid_slopes_[static_cast<std::size_t>(k) + 1] = grid_slope();
  }
  const PwlModeSystem& s = self.system(m);
  X_T = s.to_X.lazyProduct(at_start->head(s.dim));
  if (J != nullptr) {
    s.propagate(self.span_ - piece_start, S);
    multiply(s.to_X, S, *J);
  }
  return true;
}

void PwlPeriodicState::Run::first_harmonic() {
  Complex integral{0.0, 0.0};
  for (std::size_t k = 0; k < self.pieces_.size(); ++k) {
    const Piece& piece = self.pieces_[k];
    const double end = k + 1 < self.pieces_.size() ? self.pieces_[k + 1].t : self.span_;
    integral += std::exp(Complex(0.0, self.omega_ * piece.t)) * self.system(piece.mode).phased_force_integral(end - piece.t, piece.w);
  }
  const double scale = (self.half_wave_ ? 2.0 : 1.0) * self.omega_ / (std::numbers::pi * self.u0_);
  self.storage_ = scale * integral.imag();
  self.loss_ = scale * integral.real();
}

PwlVector PwlPeriodicState::Run::linear_periodic_state(int m) {
  PwlVector& unit = self.linear_start_[static_cast<std::size_t>(m)];
  if (unit.size() != 0) return self.u0_ * unit;
  const PwlModeSystem& s = self.system(m);
  const int n = branch.internal_nodes;
  PwlVector scale(2 * n);  // positions by u0 = 1, velocities by w u0
  scale << PwlVector::Ones(n), PwlVector::Constant(n, self.omega_);
  const PwlVector X0 = PwlVector::Zero(scale.size());
  PwlMatrix from = s.from_X;
  from.bottomRows(3).setZero();
  const double mirror = self.half_wave_ ? -1.0 : 1.0;
  const PwlMatrix P = s.propagator(self.span_);
  const PwlMatrix J = mirror * (s.to_X * (P * from));
  const PwlVector X_T = mirror * (s.to_X * (P * s.state_at(X0, 0.0, 1.0)));
  const PwlMatrix Js = scale.cwiseInverse().asDiagonal() * J * scale.asDiagonal();
  const PwlVector Xs = X0.cwiseQuotient(scale), Ys = X_T.cwiseQuotient(scale);
  unit = scale.cwiseProduct(self.half_wave_ ? least_norm_fixed_point(Js, Xs, Ys) : affine_fixed_point(Js, Xs, Ys));
  return self.u0_ * unit;
}

}  // namespace rheo::runtime
