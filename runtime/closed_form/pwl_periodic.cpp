#include "runtime/closed_form/pwl_periodic.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

namespace rheo::runtime {
namespace {

using Eigen::MatrixXd;
using Complex = std::complex<double>;

constexpr int kGridPerCycle = 64;
constexpr int kMaxSwitchesPerCycle = 10000;
constexpr int kMaxCycles = 60;
constexpr double kGuardTolerance = 1e-10;  // relative to each guard's scale
constexpr double kPeriodicTolerance = 1e-11;

// The fixed point of the affine map X -> J X + b (b = Y - J X0 from one application,
// Y = J X0 + b) that iterating it from X0 converges to: in the eigenvectors of J,
// xi_i = b_i / (1 - lambda_i), except along eigenvalues 1 (directions the map leaves where
// they are, such as the offset of a slider that never slips), where X0's component is kept.
// A least-squares solve of (J - I) X = -b where J's eigenvectors are too ill-conditioned.
PwlVector affine_fixed_point(const PwlMatrix& J, const PwlVector& X0, const PwlVector& Y) {
  const Eigen::VectorXd b = Y - J * X0;
  Eigen::EigenSolver<MatrixXd> eig(J);
  if (eig.info() == Eigen::Success) {
    const Eigen::MatrixXcd V = eig.eigenvectors();
    const Eigen::VectorXcd lambda = eig.eigenvalues();
    Eigen::FullPivLU<Eigen::MatrixXcd> lu(V);
    if (lu.rcond() > 1e-10) {
      const Eigen::VectorXcd xi0 = lu.solve(X0.cast<Complex>()), beta = lu.solve(b.cast<Complex>());
      Eigen::VectorXcd xi(xi0.size());
      for (Eigen::Index i = 0; i < xi.size(); ++i) xi[i] = std::abs(1.0 - lambda[i]) > 1e-9 ? beta[i] / (1.0 - lambda[i]) : xi0[i];
      return (V * xi).real();
    }
  }
  return X0 - (J - PwlMatrix::Identity(J.rows(), J.cols())).jacobiSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).setThreshold(1e-10).solve(Y - X0);
}

// The same fixed point where no eigenvalue of J is 1, by complete orthogonal decomposition (no
// heap): the half-period map (pwl_periodic.hpp), on which a never-slipping slider's offset has
// eigenvalue -1. Where one is 1 all the same, the step is the least-norm solution of
// (J - I) dX = X0 - Y.
PwlVector least_norm_fixed_point(const PwlMatrix& J, const PwlVector& X0, const PwlVector& Y) {
  Eigen::CompleteOrthogonalDecomposition<PwlMatrix> cod(J - PwlMatrix::Identity(J.rows(), J.cols()));
  cod.setThreshold(1e-10);
  return X0 - cod.solve(PwlVector(Y - X0));
}

bool same_branch(const PwlBranch& a, const PwlBranch& b) {
  if (a.internal_nodes != b.internal_nodes || a.odd != b.odd || a.switches != b.switches || a.edges.size() != b.edges.size()) return false;
  for (std::size_t i = 0; i < a.edges.size(); ++i) {
    const PwlEdge &x = a.edges[i], &y = b.edges[i];
    if (x.kind != y.kind || x.a != y.a || x.b != y.b || x.value != y.value) return false;
  }
  return true;
}

}  // namespace

// Whether a guard with value g, slope dg and curvature ddg is being left now: below zero
// beyond the tolerance, or on zero (within tol) and moving down (beyond dtol), or on zero and
// level and curving down (a switch where the slopes of both modes vanish, as when a slipping
// slider's rate reaches zero exactly as its stuck force would reach the cap).
bool leaving(double g, double dg, double ddg, double tol, double dtol) {
  if (g < -tol) return true;
  if (g > tol) return false;
  return dg < -dtol || (dg <= dtol && ddg < 0.0);
}

// One cycle followed event to event from a given state.
struct PwlPeriodicState::Run {
  PwlPeriodicState& self;
  const PwlBranch& branch;
  double step = 0.0;  // grid step T/64 [s]

  int mode_index(const PwlModeCode& code) {
    for (std::size_t i = 0; i < self.modes_.size(); ++i)
      if (self.modes_[i].code == code) return static_cast<int>(i);
    PwlModeStructure* structure = nullptr;
    for (auto& [known, st] : self.structures_)
      if (known == code) structure = &st;
    if (structure == nullptr) structure = &self.structures_.emplace_back(code, PwlModeStructure{}).second;
    // Built in place: a mode's fixed-capacity storage is tens of kilobytes.
    if (!build_pwl_mode(branch, code, self.u0_, self.omega_, self.modes_.emplace_back(), structure)) {
      self.modes_.pop_back();
      return -1;
    }
    self.grid_step_.emplace_back();
    return static_cast<int>(self.modes_.size()) - 1;
  }
  // [E; G E; G' E] for E = e^{A T/64} of mode m, G its guards and G' their rates: one product
  // gives the state a grid step on, its guards and their slopes there.
  const PwlGridStep& grid_step(int m) {
    PwlGridStep& stacked = self.grid_step_[static_cast<std::size_t>(m)];
    if (stacked.size() == 0) {
      const PwlModeSystem& s = self.modes_[static_cast<std::size_t>(m)];
      const PwlMatrix E = s.propagator(step);
      stacked.resize(s.dim + 2 * s.guards.rows(), s.dim);
      stacked << E, s.guards * E, s.guard_rates * E;
    }
    return stacked;
  }
  PwlVector advance(int m, double tau, const PwlVector& w) { return self.modes_[static_cast<std::size_t>(m)].advance(tau, w); }

  // Whether guard i of mode m is being left at state w: by its value, slope and curvature
  // (leaving()), and by its value a probe of 1e-7 T ahead where those leave it level or where
  // the curvature turns a slightly falling guard back up within the probe (a slider at the
  // drive's turning point, its slope there rounding noise of forces rates far larger).
  bool leaves(int m, int i, const PwlVector& w) {
    const PwlModeSystem& s = self.modes_[static_cast<std::size_t>(m)];
    const double tol = kGuardTolerance * s.transitions[static_cast<std::size_t>(i)].scale;
    const PwlRow G = s.guards.row(i);
    const double g = G.dot(w);
    if (g > tol) return false;
    const double probe = 1e-7 * self.period_;
    const PwlVector rate = s.A * w;
    const double slope = G.dot(rate), curvature = G.dot(s.A * rate);
    const bool turning = g >= -tol && slope < 0.0 && slope + curvature * probe > 0.0;
    if (!turning && leaving(g, slope, curvature, tol, tol * self.omega_)) return true;
    return G.dot(s.advance(probe, w)) < -tol;
  }

  // The mode reached from `m` at time t with positions and velocities X once every guard the
  // state violates has switched (a stuck slider above fy slips, a slipping one whose rate
  // points against its force sticks, ...); -1 when it does not settle.
  int settle(int m, const PwlVector& X, double t, PwlVector& w) {
    for (int attempt = 0; attempt <= 2 * static_cast<int>(branch.switches.size()) + 2; ++attempt) {
      if (m < 0) return -1;
      const PwlModeSystem& s = self.modes_[static_cast<std::size_t>(m)];
      w = s.state_at(X, t, self.u0_, self.omega_);
      int violated = -1;
      for (int i = 0; i < s.guards.rows() && violated < 0; ++i)
        if (leaves(m, static_cast<int>(i), w)) violated = static_cast<int>(i);
      if (violated < 0) return m;
      PwlModeCode code = s.code;
      const PwlTransition& tr = s.transitions[static_cast<std::size_t>(violated)];
      code[static_cast<std::size_t>(tr.which)] = tr.to;
      m = mode_index(code);
    }
    return -1;
  }

  // The first time in (0, h] at which guard row i of mode m crosses from positive to
  // negative along w(tau) = e^{A tau} w0, or infinity.
  double first_crossing(int m, int i, const PwlVector& w0, const PwlVector& w1, double h, double g0, double g1) {
    const PwlModeSystem& s = self.modes_[static_cast<std::size_t>(m)];
    const PwlRow G = s.guards.row(i), dG = s.guard_rates.row(i);
    const double tol = kGuardTolerance * s.transitions[static_cast<std::size_t>(i)].scale;
    auto value = [&](double tau) { return G.dot(advance(m, tau, w0)); };
    // The cubic through the values and slopes at both ends, c(x) = ((a3 x + a2) x + a1) x + g0
    // for tau = x h: within O(h^4) of the guard over a step of T/64, so it bounds a dip closely
    // and its root starts Newton's method a few digits from the crossing.
    const double slope0 = dG.dot(w0), slope1 = dG.dot(w1);
    const double a3 = 2.0 * (g0 - g1) + h * (slope0 + slope1), a2 = 3.0 * (g1 - g0) - h * (2.0 * slope0 + slope1), a1 = h * slope0;
    auto cubic = [&](double x) { return ((a3 * x + a2) * x + a1) * x + g0; };
    double lo = 0.0, hi = h;
    if (g1 >= 0.0) {
      // Both ends non-negative: a dip below zero needs the slope negative at 0 and positive at h;
      // only a dip the cubic brings within a tenth of the smaller end value is located.
      if (!(slope0 < 0.0 && slope1 > 0.0)) return std::numeric_limits<double>::infinity();
      double lowest = std::min(g0, g1), x_lowest = 0.5;
      const double disc = a2 * a2 - 3.0 * a3 * a1;
      if (disc >= 0.0 && a3 != 0.0)
        for (double x : {(-a2 + std::sqrt(disc)) / (3.0 * a3), (-a2 - std::sqrt(disc)) / (3.0 * a3)})
          if (x > 0.0 && x < 1.0 && cubic(x) < lowest) lowest = cubic(x), x_lowest = x;
      if (lowest > 0.1 * std::min(g0, g1)) return std::numeric_limits<double>::infinity();
      // The minimum: the slope's root, by safeguarded Newton (curvature ddG w) from the cubic's.
      const PwlRow ddG = dG * s.A;
      double a = 0.0, b = h, tau = x_lowest * h;
      for (int it = 0; it < 60 && b - a > 1e-14 * h; ++it) {
        const PwlVector w = advance(m, tau, w0);
        const double slope = dG.dot(w), curvature = ddG.dot(w);
        (slope < 0.0 ? a : b) = tau;
        double next = curvature > 0.0 ? tau - slope / curvature : 0.5 * (a + b);
        if (!(next > a && next < b)) next = 0.5 * (a + b);
        if (std::abs(next - tau) <= 1e-14 * h) break;
        tau = next;
      }
      // The last iterate is the minimum where Newton converged from one side; b where the
      // bracket closed from both.
      if (const double at_tau = value(tau); at_tau < 0.0) hi = tau;
      else if (value(b) < 0.0) hi = b;
      else return std::numeric_limits<double>::infinity();
    }
    if (g0 <= tol && leaves(m, i, w0)) return 0.0;  // the switch is now
    double tau = std::numeric_limits<double>::quiet_NaN();
    if (g0 <= tol) {
      // On the guard and not leaving it (the mode was just entered): find a point where it is
      // positive before a crossing; a sample below zero first brackets the crossing itself.
      bool found = false;
      for (int j = 0; j < 16 && !found; ++j) {
        const double sample = j == 0 ? std::min(hi, 1e-7 * self.period_) : hi * j / 16.0;
        const double v = value(sample);
        if (v > tol) lo = sample, found = true;
        else if (v < -tol) hi = sample, found = true;
      }
      if (!found) return std::numeric_limits<double>::infinity();
    } else {
      // The cubic's root in the bracket, by bisection (it is positive at lo, negative at hi).
      double a = lo / h, b = hi / h;
      if (cubic(a) > 0.0 && cubic(b) < 0.0) {
        for (int it = 0; it < 50 && b - a > 1e-13; ++it) (cubic(0.5 * (a + b)) > 0.0 ? a : b) = 0.5 * (a + b);
        tau = 0.5 * (a + b) * h;
      }
    }
    // Safeguarded Newton on the bracket [lo, hi] with g(lo) > 0 > g(hi).
    if (!(tau > lo && tau < hi)) tau = 0.5 * (lo + hi);
    for (int it = 0; it < 100; ++it) {
      const PwlVector w = advance(m, tau, w0);
      const double g = G.dot(w), dg = dG.dot(w);
      (g > 0.0 ? lo : hi) = tau;
      double next = dg != 0.0 ? tau - g / dg : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      if (std::abs(next - tau) <= 1e-15 * self.period_) return std::max(tau, next);
      if (hi - lo <= 1e-15 * self.period_) return hi;
      tau = next;
    }
    return hi;
  }

  // Switches at time t from mode m (state w) through guard i; with sensitivities S (dw/dX0)
  // applies the saltation matrix. Returns the new mode or -1.
  int switch_at(int m, int i, double t, PwlVector& w, PwlMatrix* S) {
    const PwlModeSystem& old = self.modes_[static_cast<std::size_t>(m)];
    const PwlVector X = old.to_X * w;
    PwlModeCode code = old.code;
    const PwlTransition& tr = old.transitions[static_cast<std::size_t>(i)];
    code[static_cast<std::size_t>(tr.which)] = tr.to;
    PwlVector w_new;
    const int next = settle(mode_index(code), X, t, w_new);
    if (next < 0) return -1;
    if (S != nullptr) {
      const PwlModeSystem& o = self.modes_[static_cast<std::size_t>(m)];
      const PwlModeSystem& n = self.modes_[static_cast<std::size_t>(next)];
      const PwlVector rate_old = o.A * w;
      const double slope = o.guards.row(i).dot(rate_old);
      PwlRow dt = PwlRow::Zero(S->cols());
      if (std::abs(slope) > 1e-300) dt = -(o.guards.row(i) * *S) / slope;
      PwlVector drift = -(n.A * w_new);
      drift.segment(n.nz, n.nh) += n.held_drive * (self.u0_ * self.omega_ * std::cos(self.omega_ * t));
      PwlMatrix S_new = n.from_X * (o.to_X * (*S + rate_old * dt)) + drift * dt;
      S_new.bottomRows(3).setZero();
      *S = std::move(S_new);
    }
    w = std::move(w_new);
    return next;
  }

  // Follows the map's span (a period, or half of one for an odd branch) from X0, settled from
  // mode m: X at its end and, with `J`, dX/dX0; with `record`, the pieces, switch phases and
  // first harmonic. False on failure. The sensitivities are carried by one propagator per
  // piece (from its start to its switch or the span's end), not per grid step.
  bool cycle(int& m, const PwlVector& X0, PwlVector& X_T, PwlMatrix* J, bool record) {
    PwlVector w;
    m = settle(m, X0, 0.0, w);
    if (m < 0) return false;
    PwlMatrix S;
    PwlMatrix* Sp = nullptr;
    if (J != nullptr) {
      S = self.modes_[static_cast<std::size_t>(m)].from_X;
      S.bottomRows(3).setZero();
      Sp = &S;
    }
    if (record) self.pieces_.assign(1, {0.0, m, w}), self.switch_phases_.clear();
    int switches = 0;
    double t = 0.0, piece_start = 0.0;
    PwlVector w1, g0, g1, dg0, dg1;  // the state a step on; the guards and their slopes at both ends
    Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3 * kPwlMaxDim, 1> stacked;
    bool g0_known = false;
    const int grid_steps = self.half_wave_ ? kGridPerCycle / 2 : kGridPerCycle;
    for (int k = 0; k < grid_steps; ++k) {
      const double t_end = k + 1 == grid_steps ? self.span_ : (k + 1) * step;
      while (t < t_end) {
        const PwlModeSystem& s = self.modes_[static_cast<std::size_t>(m)];
        const double h = t_end - t;
        const bool full = std::abs(h - step) <= 1e-12 * step;
        const Eigen::Index dim = s.dim, guards = s.guards.rows();
        if (!g0_known) g0.noalias() = s.guards * w, dg0.noalias() = s.guard_rates * w;
        if (full) {
          stacked.noalias() = grid_step(m) * w;
          w1 = stacked.head(dim), g1 = stacked.segment(dim, guards), dg1 = stacked.tail(guards);
        } else {
          w1 = advance(m, h, w);
          g1.noalias() = s.guards * w1, dg1.noalias() = s.guard_rates * w1;
        }
        double first = std::numeric_limits<double>::infinity();
        int fired = -1;
        for (int i = 0; i < g0.size(); ++i) {
          const double tol = kGuardTolerance * s.transitions[static_cast<std::size_t>(i)].scale;
          if (g1[i] >= 0.0 && g0[i] > tol && dg0[i] >= 0.0) continue;  // no crossing and no dip
          const double tau = first_crossing(m, i, w, w1, h, g0[i], g1[i]);
          if (tau < first) first = tau, fired = i;
        }
        if (fired < 0) {
          w = w1;
          g0 = g1, dg0 = dg1, g0_known = true;
          t = t_end;
          break;
        }
        w = advance(m, first, w);
        t += first;
        if (Sp != nullptr) *Sp = s.propagator(t - piece_start) * *Sp, piece_start = t;
        g0_known = false;
        if (++switches > kMaxSwitchesPerCycle) return false;
        m = switch_at(m, fired, t, w, Sp);
        if (m < 0) return false;
        if (record) {
          self.pieces_.push_back({t, m, w});
          self.switch_phases_.push_back(std::fmod(self.omega_ * t, 2.0 * std::numbers::pi));
        }
      }
    }
    const PwlModeSystem& s = self.modes_[static_cast<std::size_t>(m)];
    X_T = s.to_X * w;
    if (J != nullptr) *J = s.to_X * (s.propagator(self.span_ - piece_start) * S);
    return true;
  }

  // K'_1 and K''_1 of the recorded cycle, its pieces' integrals int F e^{i w t} dt in modal
  // closed form. Over a half period of an odd branch the integral is half the period's (F and
  // e^{i w t} both change sign after T/2).
  void first_harmonic() {
    Complex integral{0.0, 0.0};
    for (std::size_t k = 0; k < self.pieces_.size(); ++k) {
      const Piece& piece = self.pieces_[k];
      const double end = k + 1 < self.pieces_.size() ? self.pieces_[k + 1].t : self.span_;
      integral += std::exp(Complex(0.0, self.omega_ * piece.t)) *
                  self.modes_[static_cast<std::size_t>(piece.mode)].phased_force_integral(end - piece.t, piece.w);
    }
    const double scale = (self.half_wave_ ? 2.0 : 1.0) * self.omega_ / (std::numbers::pi * self.u0_);
    self.storage_ = scale * integral.imag();
    self.loss_ = scale * integral.real();
  }

  // The periodic state of mode m followed without its guards (the linear state every point
  // starts from): the fixed point of X -> to_X e^{A T} w(X), by one propagator over the period
  // (of X -> -to_X e^{A T/2} w(X) for an odd branch: the symmetric state, whose stuck sliders
  // hold no offset, as from rest).
  PwlVector linear_periodic_state(int m, const PwlVector& scale) {
    const PwlModeSystem& s = self.modes_[static_cast<std::size_t>(m)];
    const PwlVector X0 = PwlVector::Zero(scale.size());
    PwlMatrix from = s.from_X;
    from.bottomRows(3).setZero();
    const double mirror = self.half_wave_ ? -1.0 : 1.0;
    const PwlMatrix P = s.propagator(self.span_);
    const PwlMatrix J = mirror * (s.to_X * (P * from));
    const PwlVector X_T = mirror * (s.to_X * (P * s.state_at(X0, 0.0, self.u0_, self.omega_)));
    const PwlMatrix Js = scale.cwiseInverse().asDiagonal() * J * scale.asDiagonal();
    const PwlVector Xs = X0.cwiseQuotient(scale), Ys = X_T.cwiseQuotient(scale);
    return scale.cwiseProduct(self.half_wave_ ? least_norm_fixed_point(Js, Xs, Ys) : affine_fixed_point(Js, Xs, Ys));
  }
};

bool PwlPeriodicState::solve(const PwlBranch& branch, double u0, double omega) {
  u0_ = u0, omega_ = omega, period_ = 2.0 * std::numbers::pi / omega;
  half_wave_ = branch.odd;
  if (!same_branch(branch, structures_branch_)) structures_.clear(), structures_branch_ = branch;
  span_ = half_wave_ ? 0.5 * period_ : period_;
  const double mirror = half_wave_ ? -1.0 : 1.0;  // the map is X0 -> mirror X(span)
  storage_ = loss_ = 0.0;
  cycles_ = 0;
  modes_.clear(), grid_step_.clear(), pieces_.clear(), switch_phases_.clear();
  Run run{*this, branch, period_ / kGridPerCycle};

  const int n = branch.internal_nodes;
  PwlVector scale(2 * n);  // positions by u0, velocities by w u0
  scale << PwlVector::Constant(n, u0), PwlVector::Constant(n, u0 * omega);
  // The start: the periodic state of the mode with every slider stuck and every gap open (its
  // offsets those of rest), which is the answer where no guard is reached, as the time-stepping
  // path starts from the same linear periodic state.
  int start_mode = run.mode_index(PwlModeCode(branch.switches.size(), 0));
  if (start_mode < 0) return false;
  PwlVector X0 = run.linear_periodic_state(start_mode, scale), X_T, last_end;
  // Newton's method on X_T(X0) - X0 = 0 in scaled coordinates, globalised: a step that does not
  // lower the residual (the events moved under it) is halved once, and if that does not help
  // either, one plain cycle is taken from where the last one ended (a lightly damped fluid
  // column can otherwise trap the alternation of Newton steps and plain cycles in a loop).
  PwlVector base, step;  // the last accepted start and its Newton step
  double base_size = std::numeric_limits<double>::infinity(), fraction = 1.0;
  bool average_next = false;
  // Every cycle is recorded (pieces, switches, first harmonic): the one that closes on itself
  // is the periodic cycle.
  for (cycles_ = 1; cycles_ <= kMaxCycles; ++cycles_) {
    int m = start_mode;
    PwlMatrix J;
    if (!run.cycle(m, X0, X_T, &J, true)) {
      // A start no mode can settle (the linear state, or a Newton step, may hold a slider
      // beyond its cap): start the first cycle from rest instead (the periodic state slips then
      // anyway), a later one from where the last cycle ended, a state the branch reached.
      if (cycles_ == 1 ? X0.isZero() : X0 == last_end) return false;
      X0 = cycles_ == 1 ? PwlVector(PwlVector::Zero(2 * n)) : last_end;
      m = start_mode;
      if (!run.cycle(m, X0, X_T, &J, true)) return false;
    }
    X_T *= mirror;
    J *= mirror;
    last_end = X_T;
    const PwlVector residual = (X_T - X0).cwiseQuotient(scale);
    const double size = residual.cwiseAbs().maxCoeff();
    if (!std::isfinite(size)) return false;
    if (size <= kPeriodicTolerance) {
      run.first_harmonic();
      if (half_wave_) {
        // The other half is this one mirrored: its switches half a period later.
        const std::size_t n_half = switch_phases_.size();
        for (std::size_t k = 0; k < n_half; ++k) switch_phases_.push_back(switch_phases_[k] + std::numbers::pi);
        return true;
      }
      // The extrema are taken as max F = -min F (periodic_closed_form.hpp): the force must be
      // half-wave symmetric, F(theta + pi) = -F(theta), as it is wherever the periodic state is
      // unique up to offsets that carry no force; checked at 16 phases.
      double asymmetry = 0.0, largest = 0.0;
      for (int k = 0; k < 16; ++k) {
        const double theta = (k + 0.5) * std::numbers::pi / 16.0, f = force(theta);
        asymmetry = std::max(asymmetry, std::abs(f + force(theta + std::numbers::pi)));
        largest = std::max(largest, std::abs(f));
      }
      return asymmetry <= 1e-8 * largest;
    }
    if (half_wave_) {
      PwlModeCode mirrored = modes_[static_cast<std::size_t>(m)].code;
      for (auto& state : mirrored) state = static_cast<std::int8_t>(-state);
      m = run.mode_index(mirrored);
      if (m < 0) return false;
    }
    start_mode = m;
    if (average_next) {
      // A plain step on the half map is two, X1 = P(X0) and X2 = P(X1), averaged: a slider
      // offset the map flips (eigenvalue -1) cancels instead of alternating, and a state the
      // map reaches in one step stays where it is.
      average_next = false;
      X0 = 0.5 * (X0 + X_T);
      continue;
    }
    if (size < base_size) {
      base_size = size, base = X0, fraction = 1.0;
      const PwlMatrix Js = scale.cwiseInverse().asDiagonal() * J * scale.asDiagonal();
      const PwlVector Xs = X0.cwiseQuotient(scale), Ys = X_T.cwiseQuotient(scale);
      step = scale.cwiseProduct(half_wave_ ? least_norm_fixed_point(Js, Xs, Ys) : affine_fixed_point(Js, Xs, Ys)) - X0;
      X0 = base + step;
    } else if (fraction == 1.0) {
      fraction *= 0.5;
      X0 = base + fraction * step;
    } else {
      base_size = std::numeric_limits<double>::infinity();
      X0 = X_T;
      average_next = half_wave_;
    }
  }
  return false;
}

PwlVector PwlPeriodicState::state_at_phase(double theta, int& mode, double& sign) const {
  double t = std::fmod(theta / omega_, period_);
  if (t < 0.0) t += period_;
  sign = 1.0;
  if (half_wave_ && t >= span_) t -= span_, sign = -1.0;
  auto it = std::upper_bound(pieces_.begin(), pieces_.end(), t, [](double value, const Piece& p) { return value < p.t; });
  const Piece& piece = it == pieces_.begin() ? pieces_.front() : *std::prev(it);
  mode = piece.mode;
  return modes_[static_cast<std::size_t>(mode)].advance(t - piece.t, piece.w);
}

double PwlPeriodicState::force(double theta) const {
  int m = 0;
  double sign = 1.0;
  const PwlVector w = state_at_phase(theta, m, sign);
  return sign * modes_[static_cast<std::size_t>(m)].force.dot(w);
}

void PwlPeriodicState::derivatives(double theta, double& first, double& second) const {
  int m = 0;
  double sign = 1.0;
  const PwlVector w = state_at_phase(theta, m, sign);
  const PwlModeSystem& s = modes_[static_cast<std::size_t>(m)];
  const PwlVector rate = s.A * w;
  first = sign * s.force.dot(rate) / omega_;
  second = sign * s.force.dot(s.A * rate) / (omega_ * omega_);
}

}  // namespace rheo::runtime
