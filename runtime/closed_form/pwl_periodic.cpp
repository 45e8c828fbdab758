#include "runtime/closed_form/pwl_periodic.hpp"

#include "runtime/closed_form/pwl_cycle.hpp"
#include "runtime/closed_form/pwl_describing.hpp"
#include "runtime/closed_form/pwl_fixed_point.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace rheo::runtime {
namespace {

// Cycles of the globalised Newton shooting, then of plain cycles (settle_by_cycles) where that
// did not close; time stepping's default is 400 cycles too.
constexpr int kMaxCycles = 60;
constexpr int kMaxSettlingCycles = 400;
constexpr double kPeriodicTolerance = 1e-11;
// Newton's iterations on the map of one sequence of switches (Run::replay) between followed
// cycles: at most, and the residual (scaled, as the shooting's) at which the next followed
// cycle is expected to close.
constexpr int kMaxReplays = 8;
constexpr double kReplayTolerance = 1e-13;
constexpr double kQuadraticReplay = 1e-5;
constexpr std::size_t kMaxSolved = 2048;  // solves kept per branch (about 1.5 kB each)
constexpr std::size_t kMaxModes = 192;    // modes kept per branch (about 65 kB each, most of it capacity never touched)

bool same_branch(const PwlBranch& a, const PwlBranch& b) {
  if (a.internal_nodes != b.internal_nodes || a.odd != b.odd || a.switches != b.switches || a.edges.size() != b.edges.size()) return false;
  for (std::size_t i = 0; i < a.edges.size(); ++i) {
    const PwlEdge &x = a.edges[i], &y = b.edges[i];
    if (x.kind != y.kind || x.a != y.a || x.b != y.b || x.value != y.value || x.cap_neg != y.cap_neg || x.center != y.center) return false;
  }
  return true;
}

bool same_start(const PwlStart& a, const PwlStart& b) { return a.mode == b.mode && a.X0.size() == b.X0.size() && a.X0 == b.X0; }

}  // namespace

bool PwlPeriodicState::solve(const PwlBranch& branch, double u0, double omega, const PwlStart* from) {
  u0_ = u0, omega_ = omega, period_ = 2.0 * std::numbers::pi / omega;
  half_wave_ = branch.odd;
  if (!same_branch(branch, structures_branch_)) structure_count_ = 0, structures_branch_ = branch, solved_count_ = 0, mode_count_ = 0;
  if (mode_count_ >= kMaxModes) mode_count_ = 0;  // built again as needed: a mode is the same whenever it is built
  active_.clear();
  for (std::size_t i = 0; i < mode_count_; ++i)
    if (mode_omega_[i] == omega) active_.push_back(static_cast<int>(i));
  span_ = half_wave_ ? 0.5 * period_ : period_;
  storage_ = loss_ = 0.0;
  cycles_ = 0;
  pieces_.clear(), switch_phases_.clear();
  last_piece_ = kNoPiece, recent_count_ = recent_next_ = 0;
  start_.X0.resize(0), start_.mode.clear(), start_.allowed.resize(0);
  Run run{*this, branch, period_ / kPwlGridPerCycle};
  // Only an odd branch is warm-started: its periodic state is unique (the half map flips a
  // never-slipping slider's offset, so its fixed point has none), where a full-period fixed
  // point keeps the offsets of its start.
  if (!branch.odd) from = nullptr;
  // A cold solve restores a cold one; a warm one any that started its closing cycle at FROM
  // (the warm solve's first cycle would be that cycle, bit for bit).
  for (std::size_t k = 0; k < solved_count_; ++k) {
    const std::size_t i = (solved_next_ + k) % solved_count_;
    const Solved& solved = solved_[i];
    if (solved.u0 != u0 || solved.omega != omega) continue;
    if (from == nullptr ? solved.warm : !(solved.ok && same_start(solved.start, *from))) continue;
    solved_next_ = (i + 1) % solved_count_;
    return restore(run, solved);
  }
  if (from != nullptr && shoot(run, from)) {
    remember(true, true);
    return true;
  }
  const bool ok = shoot(run, nullptr);
  remember(ok, false);
  return ok;
}

bool PwlPeriodicState::restore(Run& run, const Solved& solved) {
  cycles_ = solved.cycles;
  if (!solved.ok) return false;
  storage_ = solved.storage, loss_ = solved.loss;
  start_.X0 = solved.start.X0;
  start_.mode.assign(solved.start.mode.begin(), solved.start.mode.end());
  start_.allowed = solved.start.allowed;
  switch_phases_ = solved.switch_phases;
  grid_slopes_ = solved.grid_slopes;
  pieces_ = solved.pieces;
  thread_local std::vector<int> modes;
  modes.clear();
  for (const PwlModeCode& code : solved.codes) {
    modes.push_back(run.mode_index(code));
    if (modes.back() < 0) return false;  // not reached: the mode was built when the point was solved
  }
  for (Piece& piece : pieces_) piece.mode = modes[static_cast<std::size_t>(piece.mode)];
  return true;
}

void PwlPeriodicState::remember(bool ok, bool warm) {
  if (solved_count_ == kMaxSolved) return;
  if (solved_count_ == solved_.size()) solved_.emplace_back();
  Solved& s = solved_[solved_count_++];
  s.u0 = u0_, s.omega = omega_, s.ok = ok, s.warm = warm, s.cycles = cycles_;
  s.storage = storage_, s.loss = loss_;
  s.switch_phases = switch_phases_;
  s.grid_slopes = grid_slopes_;
  s.start.X0 = start_.X0;
  s.start.mode.assign(start_.mode.begin(), start_.mode.end());
  s.start.allowed = start_.allowed;
  s.pieces = pieces_;
  s.codes.clear();
  for (Piece& piece : s.pieces) {
    const PwlModeCode& code = system(piece.mode).code;
    const auto known = std::find(s.codes.begin(), s.codes.end(), code);
    piece.mode = static_cast<int>(known - s.codes.begin());
    if (known == s.codes.end()) s.codes.push_back(code);
  }
}

bool PwlPeriodicState::shoot(Run& run, const PwlStart* from) {
  const PwlBranch& branch = run.branch;
  const double u0 = u0_, omega = omega_;
  const double mirror = half_wave_ ? -1.0 : 1.0;  // the map is X0 -> mirror X(span)

  const int n = branch.internal_nodes;
  PwlVector scale(2 * n);  // positions by u0, velocities by w u0
  scale << PwlVector::Constant(n, u0), PwlVector::Constant(n, u0 * omega);
  // The start: the periodic state of the mode with every slider stuck and every gap open (its
  // offsets those of rest), which is the answer where no guard is reached, as the time-stepping
  // path starts from the same linear periodic state.
  // A warm start (pwl_warm_start.hpp) instead: the periodic state of nearby parameters and the
  // mode its closing cycle settled from.
  const bool warm = from != nullptr && from->X0.size() == 2 * n && from->mode.size() == branch.switches.size();
  if (from != nullptr && !warm) return false;
  int start_mode = run.mode_index(warm ? from->mode : PwlModeCode(branch.switches.size(), 0));
  if (start_mode < 0) return false;
  PwlVector X0, X_T, last_end;
  if (warm) X0 = from->X0;
  else if (!half_wave_ || !pwl_describing_start(branch, u0, omega, X0)) X0 = run.linear_periodic_state(start_mode);
  // Newton's method on X_T(X0) - X0 = 0 in scaled coordinates, globalised: a step that does not
  // lower the residual (the events moved under it) is halved once, and if that does not help
  // either, one plain cycle is taken from where the last one ended (a lightly damped fluid
  // column can otherwise trap the alternation of Newton steps and plain cycles in a loop).
  PwlVector base, step;  // the last accepted start and its Newton step
  double base_size = std::numeric_limits<double>::infinity(), fraction = 1.0;
  bool average_next = false;
  // Whether the last step was Newton's from a residual below kQuadratic: its cycle should close
  // (Newton converges quadratically where the events keep their order), so it is followed
  // without sensitivities, and again with them in the rare case it does not close.
  constexpr double kQuadratic = 1e-6;
  bool expect_closed = false;
  // The periodic test, per coordinate of the scaled residual X_T - X0: a start within
  // kPeriodicTolerance of the fixed point leaves up to (1 + sum_j |Js_ij|) kPeriodicTolerance in
  // coordinate i, Js the map's Jacobian in the scales (of the last Newton step's cycle). Where
  // the map amplifies its start (a stiff, nearly undamped node: 2e-9 kg behind 1232 N/mm, whose
  // velocity answers its position by omega_n / omega ~ 1.5e6) rounding in the start alone leaves
  // more than kPeriodicTolerance in that velocity, and a test on the residual alone never passed.
  // A warm start's first cycle is tested as the recorded closing cycle was (PwlStart::allowed).
  PwlVector allowed = warm && from->allowed.size() == 2 * n ? from->allowed : PwlVector(PwlVector::Constant(2 * n, kPeriodicTolerance));
  // Every cycle is recorded (pieces, switches, first harmonic): the one that closes on itself
  // is the periodic cycle.
  for (cycles_ = 1; cycles_ <= kMaxCycles; ++cycles_) {
    int m = start_mode;
    PwlMatrix J;
    if (!run.cycle(m, X0, X_T, expect_closed ? nullptr : &J, true)) {
      // A start no mode can settle (the linear state, or a Newton step, may hold a slider
      // beyond its cap): start the first cycle from rest instead (the periodic state slips then
      // anyway), a later one from where the last cycle ended, a state the branch reached.
      if (warm && cycles_ == 1) return false;  // the cold start then
      if (cycles_ == 1 ? X0.isZero() : X0 == last_end) return false;
      X0 = cycles_ == 1 ? PwlVector(PwlVector::Zero(2 * n)) : last_end;
      m = start_mode;
      if (!run.cycle(m, X0, X_T, &J, true)) return false;
      expect_closed = false;
    }
    X_T *= mirror;
    last_end = X_T;
    const PwlVector residual = (X_T - X0).cwiseQuotient(scale);
    const double size = residual.cwiseAbs().maxCoeff();
    if (!std::isfinite(size)) return false;
    if (size <= kPeriodicTolerance) return close(run, X0, start_mode, PwlVector());
    if ((residual.cwiseAbs().array() <= allowed.array()).all()) return close(run, X0, start_mode, allowed);
    if (expect_closed) {  // it did not close: the same cycle again, with its sensitivities
      expect_closed = false;
      m = start_mode;
      if (!run.cycle(m, X0, X_T, &J, true)) return false;
      X_T *= mirror;
    }
    J *= mirror;
    m = next_start(run, m);
    if (m < 0) return false;
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
      allowed = kPeriodicTolerance * (PwlVector::Ones(2 * n) + Js.cwiseAbs().rowwise().sum());
      const PwlVector Xs = X0.cwiseQuotient(scale), Ys = X_T.cwiseQuotient(scale);
      step = scale.cwiseProduct(half_wave_ ? least_norm_fixed_point(Js, Xs, Ys) : affine_fixed_point(Js, Xs, Ys)) - X0;
      X0 = base + step;
      expect_closed = size <= kQuadratic || converge_on_sequence(run, X0, scale, mirror, size);
    } else if (fraction == 1.0) {
      fraction *= 0.5;
      X0 = base + fraction * step;
    } else {
      base_size = std::numeric_limits<double>::infinity();
      X0 = X_T;
      average_next = half_wave_;
    }
  }
  // A warm start's failure is followed by the cold one (solve), which settles by plain cycles.
  return from == nullptr && settle_by_cycles(run, last_end, start_mode, scale, mirror);
}

int PwlPeriodicState::next_start(Run& run, int end_mode) {
  if (!half_wave_) return end_mode;
  PwlModeCode mirrored = system(end_mode).code;
  for (auto& state : mirrored) state = static_cast<std::int8_t>(-state);
  return run.mode_index(mirrored);
}

bool PwlPeriodicState::close(Run& run, const PwlVector& X0, int start_mode, const PwlVector& allowed) {
  start_.X0 = X0;
  start_.allowed = allowed;
  start_.mode.assign(system(start_mode).code.begin(), system(start_mode).code.end());
  run.first_harmonic();
  if (half_wave_) {
    // The other half is this one mirrored: its switches half a period later.
    const std::size_t n_half = switch_phases_.size();
    for (std::size_t k = 0; k < n_half; ++k) switch_phases_.push_back(switch_phases_[k] + std::numbers::pi);
  }
  // Otherwise the whole period was followed: the force's extrema are searched over all of it
  // (periodic_closed_form.cpp), so it need not be half-wave symmetric.
  return true;
}

bool PwlPeriodicState::settle_by_cycles(Run& run, PwlVector X0, int start_mode, const PwlVector& scale, double mirror) {
  PwlVector X_T, reached = X0;  // the last plain cycle's end, a state the branch reached
  int reached_mode = start_mode;
  double last = std::numeric_limits<double>::infinity();
  for (int k = 0; k < kMaxSettlingCycles; ++k, ++cycles_) {
    int m = start_mode;
    if (!run.cycle(m, X0, X_T, nullptr, true)) {
      // A start from Newton on a sequence no mode settles (a slider held beyond its cap): the
      // plain cycles go on from where the last one ended.
      if (X0 == reached) return false;
      X0 = reached, start_mode = reached_mode;
      continue;
    }
    X_T *= mirror;
    const double size = (X_T - X0).cwiseQuotient(scale).cwiseAbs().maxCoeff();
    if (!std::isfinite(size)) return false;
    if (size <= kPeriodicTolerance) return close(run, X0, start_mode, PwlVector());
    m = next_start(run, m);
    if (m < 0) return false;
    start_mode = m;
    reached = X_T, reached_mode = m;
    PwlVector next = X_T;
    if (!(size < last && converge_on_sequence(run, next, scale, mirror, size))) next = X_T;
    last = size;
    X0 = next;
  }
  return false;
}

bool PwlPeriodicState::converge_on_sequence(Run& run, PwlVector& X0, const PwlVector& scale, double mirror, double last) {
  if (!replays_ || pieces_.size() < 2 || !half_wave_) return false;
  PwlVector X = X0, Y;
  PwlMatrix J;
  for (int k = 0; k < kMaxReplays; ++k) {
    if (!run.replay(X, Y, J)) return false;
    Y *= mirror;
    const double size = (Y - X).cwiseQuotient(scale).cwiseAbs().maxCoeff();
    if (!(size < last)) return false;  // not converging (or not finite)
    if (size <= kReplayTolerance) {
      X0 = X;
      return true;
    }
    // Newton's residual after this step, C size^2 with C from the last step's.
    const double expected = size * size * (size / (last * last));
    last = size;
    J *= mirror;
    const PwlMatrix Js = scale.cwiseInverse().asDiagonal() * J * scale.asDiagonal();
    X = scale.cwiseProduct(least_norm_fixed_point(Js, X.cwiseQuotient(scale), Y.cwiseQuotient(scale)));
    if (size <= kQuadraticReplay && expected <= kReplayTolerance) {
      X0 = X;
      return true;
    }
  }
  return false;
}

std::size_t PwlPeriodicState::piece_at_phase(double theta, double& t, double& sign) const {
  t = std::fmod(theta / omega_, period_);
  if (t < 0.0) t += period_;
  sign = 1.0;
  if (half_wave_ && t >= span_) t -= span_, sign = -1.0;
  auto it = std::upper_bound(pieces_.begin(), pieces_.end(), t, [](double value, const Piece& p) { return value < p.t; });
  return it == pieces_.begin() ? 0 : static_cast<std::size_t>(std::prev(it) - pieces_.begin());
}

const PwlVector& PwlPeriodicState::state_at_phase(double theta, int& mode, double& sign) const {
  double t = 0.0;
  const std::size_t k = piece_at_phase(theta, t, sign);
  mode = pieces_[k].mode;
  return state_in_piece(theta, k, t);
}

const PwlVector& PwlPeriodicState::state_in_piece(double theta, std::size_t k, double t) const {
  for (std::size_t i = 0; i < recent_count_; ++i)
    if (recent_[i].theta == theta) return recent_[i].w;
  const Piece& piece = pieces_[k];
  const PwlModeSystem& s = system(piece.mode);
  // Nudged from the last state asked for where it is in the same piece and near (the
  // iterations of an extremum's search), else the flow from the piece's start.
  if (k != last_piece_ || !s.nudge(t - last_t_, last_w_, last_w_)) last_w_ = s.advance(t - piece.t, piece.w);
  last_piece_ = k, last_t_ = t;
  Recent& kept = recent_[recent_next_];
  kept.theta = theta, kept.w = last_w_;
  recent_next_ = (recent_next_ + 1) % kRecent, recent_count_ = std::min(recent_count_ + 1, kRecent);
  return last_w_;
}

void PwlPeriodicState::slopes(const double* theta, int count, double offset, double* first) const {
  const double grid = period_ / kPwlGridPerCycle;
  std::size_t current = pieces_.size();  // the piece w is in (none yet)
  double current_sign = 0.0, current_t = 0.0;
  PwlVector w, next;
  PwlRow slope_row;  // force A / omega of the current piece's mode
  for (int j = 0; j < count; ++j) {
    double t = 0.0, sign = 1.0;
    const std::size_t k = piece_at_phase(theta[j] + offset, t, sign);
    const int mode = pieces_[k].mode;
    const PwlModeSystem& s = system(mode);
    if (k == current && sign == current_sign && t > current_t) {
      const PwlGridStep& E = grid_step_[static_cast<std::size_t>(mode)];
      const double gap = t - current_t;
      if (E.size() != 0 && std::abs(gap - grid) <= 1e-9 * grid) next.noalias() = E.topRows(s.dim).lazyProduct(w), w = next;
      else if (!s.nudge(gap, w, w)) w = s.advance(gap, w);
    } else {
      w = state_in_piece(theta[j] + offset, k, t);
      slope_row = s.force_rate / omega_;
      current = k, current_sign = sign;
    }
    current_t = t;
    first[j] = sign * slope_row.dot(w);
  }
}

double PwlPeriodicState::force(double theta) const {
  int m = 0;
  double sign = 1.0;
  const PwlVector& w = state_at_phase(theta, m, sign);
  return sign * system(m).force.dot(w);
}

void PwlPeriodicState::derivatives(double theta, double& first, double& second) const {
  int m = 0;
  double sign = 1.0;
  const PwlVector& w = state_at_phase(theta, m, sign);
  const PwlModeSystem& s = system(m);
  first = sign * s.force_rate.dot(w) / omega_;
  second = sign * s.force_curvature.dot(w) / (omega_ * omega_);
}

}  // namespace rheo::runtime
