// The periodic steady state of a piecewise-linear branch (pwl_branch.hpp) under the drive
// u = u0 sin(w t), found exactly: no time step and no cycles run until they repeat.
//
// Within a mode the branch state moves by the matrix exponential of its augmented linear ODE
// (pwl_mode.hpp), applied in modal closed form (pwl_flow.cpp). A cycle is followed event to event: the guards are checked at 64 points
// per cycle, where a guard changes sign (or a cubic through its values and slopes at both ends
// dips below zero) the crossing is located by safeguarded Newton on the exact trajectory, and
// the branch switches mode there, settling any guard the new mode violates at once.
//
// The one-cycle map X(0) -> X(T) of node positions and velocities is affine for a fixed
// sequence of events. The periodic state is its fixed point, found by Newton's method
// (shooting): the Jacobian is propagated with the state, through each event by its saltation
// matrix, J_new = dw_new/dX (dw/dX_old + A_old w dt) - A_new w_new dt with
// dt = -g.dw/(g.A_old w) (g the guard that fired), and within a mode piece by piece in its
// modal coordinates (PwlModeSystem::propagate). Directions the map leaves unchanged (a slider that never slips keeps any offset) keep
// the start's value: the branch starts at rest, as time stepping does, and (J - I) is solved
// in the least-squares sense. A Newton step that does not lower the residual is halved once,
// then a plain cycle is taken (numerics.md).
//
// A branch that is not odd (one-sided caps, an off-centre gap) is followed over the whole
// period, its fixed point that of the full-period map; where that map leaves directions
// unchanged (a slider that shakes down and stays stuck keeps the offset the first cycles left
// it) the fixed point keeps the start's component, as time stepping from rest keeps what its
// first cycles leave: the two agree where the slip in every cycle fixes the offsets. A branch
// that ratchets (one-sided caps before a dashpot: the slider and the dashpot drift by the same
// amount every period, the force periodic, the positions not) has no fixed point: time-stepped.
//
// An odd branch (PwlBranch::odd: every law odd) under an odd drive, u(t + T/2) = -u(t), has
// the mirrored state -X(t + T/2) as a solution too; its periodic state is the half-wave
// symmetric one, the fixed point of the half-period map X0 -> -X(T/2), found the same way at
// half the cost. It is the state time stepping reaches from rest: rest and the stuck linear
// periodic start are symmetric, and the offsets of sliders that never slip stay zero (the half
// map flips them, so its fixed point has none). An odd branch with one slider that slips
// starts from a describing-function estimate of that state instead (pwl_describing.hpp),
// symmetric too and a function of the point alone.
//
// The cycle then yields the first harmonic exactly, K'_1 + i K''_1 = (w/(pi u0)) int_0^T
// F(t) e^{i w t} dt, each piece's integral in modal closed form, and
// F, dF/dtheta and d2F/dtheta2 at any phase theta = w t for the extrema (eqs. 1.2, 5.26).
#pragma once

#include "runtime/closed_form/pwl_mode.hpp"
#include "runtime/closed_form/pwl_warm_start.hpp"

#include <array>
#include <deque>
#include <utility>
#include <vector>

namespace rheo::runtime {

class PwlPeriodicState {
 public:
  // REPLAYS: whether the shooting converges Newton's method on the map of a followed cycle's
  // sequence of switches (Run::replay) before following the next cycle; false follows a cycle
  // per Newton step, as a second path to the same periodic states (pwl_replay_test).
  explicit PwlPeriodicState(bool replays = true) : replays_(replays) {}
  // Not copyable or movable: its mode table (systems_) holds the addresses of its own modes.
  PwlPeriodicState(const PwlPeriodicState&) = delete;
  PwlPeriodicState& operator=(const PwlPeriodicState&) = delete;

  // False when the event-driven path cannot settle this branch: a mode that would be
  // indeterminate, more than 10000 switches in a cycle, or no fixed point after 60 cycles of
  // Newton's shooting and 400 plain cycles after them (settle_by_cycles). The
  // caller then time-steps the point. A solve of the same branch (every edge and value equal)
  // at a drive solved before (up to 2048 drives) restores that result.
  // With FROM (pwl_warm_start.hpp: the start() of a solve of this point with nearby parameters)
  // an odd branch's shooting starts there, not at the stuck linear state; from the cold start
  // where that fails. A warm solve restores a kept solve only where that one started its
  // closing cycle at FROM itself (the same bits the warm solve's first cycle gives), and a cold
  // solve never restores a warm one: a result does not depend on which solves a thread kept.
  bool solve(const PwlBranch& branch, double u0, double omega, const PwlStart* from = nullptr);
  // Where the cycle that closed on itself started (after a successful solve or restore).
  const PwlStart& start() const { return start_; }
  // Whether the steady force is half-wave symmetric, F(theta + pi) = -F(theta), by
  // construction (an odd branch): then max F = -min F. Otherwise, a branch with uneven laws
  // (one-sided caps, an off-centre gap), the extrema are those of the whole period.
  bool half_wave() const { return half_wave_; }

  double storage() const { return storage_; }  // K'_1 [N/mm]
  double loss() const { return loss_; }        // K''_1 [N/mm]
  int cycles() const { return cycles_; }       // cycles followed (the shooting iterations and the last)

  // At phase theta = w t [rad] of the steady cycle (any real theta): F [N], dF/dtheta, d2F/dtheta2.
  double force(double theta) const;
  void derivatives(double theta, double& first, double& second) const;
  // dF/dtheta at the phases theta[j] + offset, j < count, into first[j]: the state is carried
  // from sample to sample within a piece (as derivatives(), to rounding), by the grid step's
  // propagator where samples lie a grid step (T/64) apart and that propagator was built in the
  // shooting, else by the flow, and restarted where a piece or the half period ends. The
  // force's maximum search samples its slope so (periodic_closed_form.cpp).
  void slopes(const double* theta, int count, double offset, double* first) const;
  // dF/dtheta at theta = k 2 pi/64 (any integer k), the grid points of the shooting's steady
  // cycle: recorded as that cycle passed them (as slopes() would give them, to rounding). At a
  // switch on a grid point, the slope after it.
  double grid_slope(int k) const {
    const int n = static_cast<int>(grid_slopes_.size()) - 1;  // grid steps of the span: 32 or 64
    const int cycle = half_wave_ ? 2 * n : n;                 // 64
    k %= cycle;
    if (k < 0) k += cycle;
    return (k >= n ? -grid_slopes_[static_cast<std::size_t>(k - n)] : grid_slopes_[static_cast<std::size_t>(k)]) / omega_;
  }
  // Phases in [0, 2 pi) at which a slider or gap switches in the steady cycle (kinks of F).
  const std::vector<double>& switch_phases() const { return switch_phases_; }

 private:
  struct Piece {     // from the span's start or a switch to the next switch or the span's end
    double t = 0.0;  // start [s]
    int mode = 0;
    PwlVector w;
  };
  struct Run;
  // A solve kept for its drive (u0, omega) while the branch stays the same: a fit's evaluation
  // that changed only parameters outside this branch (the columns of a Jacobian) restores it,
  // its pieces' modes rebuilt as they were, instead of shooting again; the same result to the
  // last bit. Modes by index into codes.
  struct Solved {
    double u0 = 0.0, omega = 0.0;
    bool ok = false;
    bool warm = false;  // shot from a warm start
    int cycles = 0;
    double storage = 0.0, loss = 0.0;
    std::vector<Piece> pieces;
    std::vector<PwlModeCode> codes;
    std::vector<double> switch_phases;
    std::vector<double> grid_slopes;
    PwlStart start;
  };

  bool replays_ = true;
  double u0_ = 0.0, omega_ = 0.0, period_ = 0.0;
  bool half_wave_ = false;  // an odd branch: the pieces cover [0, T/2), the rest is their mirror
  double span_ = 0.0;       // T/2 or T [s]
  double storage_ = 0.0, loss_ = 0.0;
  int cycles_ = 0;
  PwlStart start_;
  // The modes built for structures_branch_ are the first mode_count_, each for the frequency
  // mode_omega_ holds (a mode serves every amplitude: pwl_mode.hpp), kept across solves (the
  // points of a grid) up to kMaxModes; the rest are storage kept from earlier solves, rebuilt in
  // place (a deque, so references stay valid as modes are added). active_ indexes those of this
  // solve's frequency.
  std::deque<PwlModeSystem> modes_;
  std::vector<PwlModeSystem*> systems_;  // &modes_[i]: indexing a deque costs more than it should in the inner loops
  const PwlModeSystem& system(int i) const { return *systems_[static_cast<std::size_t>(i)]; }
  std::vector<double> mode_omega_;
  std::size_t mode_count_ = 0;
  std::vector<int> active_;
  // The drive-independent parts of every mode built for structures_branch_, the first
  // structure_count_, kept across solves (the points of a grid) until a solve is given another
  // branch (new parameters); the rest is storage kept from earlier branches, refilled in place
  // (a structure's complex storage, ~18 kB, is cleared when constructed).
  std::deque<std::pair<PwlModeCode, PwlModeStructure>> structures_;
  std::size_t structure_count_ = 0;
  PwlBranch structures_branch_;
  // Per mode (as modes_), built when first needed: e^{A T/64} stacked over the guards, the
  // guard rates and the force's rate it leads to; empty until then.
  using PwlGridStep = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3 * kPwlMaxDim + 1, kPwlMaxDim>;
  std::vector<PwlGridStep> grid_step_;
  // Per mode (as modes_): its linear periodic state at unit amplitude (Run::linear_periodic_state), empty until needed.
  std::vector<PwlVector> linear_start_;
  std::vector<Piece> pieces_;
  std::vector<int> fired_;  // the guard of pieces_[k]'s mode through which piece k + 1 began
  std::vector<double> switch_phases_;
  std::vector<double> grid_slopes_;        // dF/dt [N/s] at the span's grid points k T/64, k = 0..32 or 64 (grid_slope())
  PwlModeCode settle_code_, switch_code_;  // scratch of Run::settle and Run::switch_at (no allocation per event)
  PwlVector probe_;                        // scratch of Run::leaves
  // Solves of structures_branch_, the first solved_count_ (storage beyond is reused); a lookup
  // starts at solved_next_, after the last one found (a grid's points come in order).
  std::vector<Solved> solved_;
  std::size_t solved_count_ = 0, solved_next_ = 0;

  bool shoot(Run& run, const PwlStart* from);
  // Records the cycle just followed from X0 in START_MODE, which closed on itself, as the
  // periodic one. True.
  bool close(Run& run, const PwlVector& X0, int start_mode, const PwlVector& allowed);  // allowed: PwlStart::allowed
  // The mode the next cycle starts in after one ending in END_MODE: that mode, mirrored on the
  // half map (its sliders' slip reversed). -1 where it cannot be built.
  int next_start(Run& run, int end_mode);
  // Where the shooting's Newton steps do not settle (a lightly damped column near resonance
  // behind a weak slider changes its sequence of switches at every step): plain cycles of the
  // exact map from X0, a state the branch reached, in START_MODE, as time stepping settles, with
  // Newton on a cycle's sequence of switches (converge_on_sequence) wherever the residual fell
  // (where a cycle from Newton's start fails, from the last plain cycle's end again). At most
  // kMaxSettlingCycles, for cold solves only (a warm one that fails is solved cold); false
  // where they do not close.
  bool settle_by_cycles(Run& run, PwlVector X0, int start_mode, const PwlVector& scale, double mirror);
  // Newton's method from X0 (the Newton step from the last recorded cycle, whose residual was
  // LAST) on the map of that cycle's sequence of switches (Run::replay) until its residual is
  // at rounding: true with X0 that fixed point, which the next followed cycle confirms where
  // the periodic state keeps that sequence. False (X0 untouched) where the sequence cannot be
  // kept or Newton does not converge on it.
  bool converge_on_sequence(Run& run, PwlVector& X0, const PwlVector& scale, double mirror,
                            double last);  // the periodic state by shooting (the solve proper), from FROM or cold
  bool restore(Run& run, const Solved& solved);
  void remember(bool ok, bool warm);

  // The state at phase theta, its mode, and the sign its force takes there (-1 in the
  // mirrored half of an odd branch). Valid until the next call.
  const PwlVector& state_at_phase(double theta, int& mode, double& sign) const;
  // The same in piece k at time t into the span (piece_at_phase of theta).
  const PwlVector& state_in_piece(double theta, std::size_t k, double t) const;
  // The last state state_at_phase found: in piece last_piece_ at time last_t_ into the span
  // (kNoPiece: none since the solve).
  static constexpr std::size_t kNoPiece = static_cast<std::size_t>(-1);
  mutable std::size_t last_piece_ = kNoPiece;
  mutable double last_t_ = 0.0;
  mutable PwlVector last_w_;
  // The last kRecent states found, by their phase: the force's maximum search asks for the
  // state at a piece's end for the force there and again for the slope (pieces on either side).
  static constexpr std::size_t kRecent = 4;
  struct Recent {
    double theta = 0.0;
    PwlVector w;
  };
  mutable std::array<Recent, kRecent> recent_;
  mutable std::size_t recent_count_ = 0, recent_next_ = 0;
  // The piece holding phase theta, the time t [s] into the span there and the sign as above.
  std::size_t piece_at_phase(double theta, double& t, double& sign) const;
};

}  // namespace rheo::runtime
