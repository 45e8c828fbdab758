// The cycle follower of the event path (pwl_periodic.hpp): one span of the cycle map (a period,
// or half of one for an odd branch) followed event to event from a given state, with the
// sensitivities of the shooting Newton step, the recorded pieces and the first harmonic.
// Internal to pwl_periodic.cpp and pwl_cycle.cpp.
#pragma once

#include "runtime/closed_form/pwl_periodic.hpp"

namespace rheo::runtime {

inline constexpr int kPwlGridPerCycle = 64;  // guard checks per cycle

struct PwlPeriodicState::Run {
  PwlPeriodicState& self;
  const PwlBranch& branch;
  double step = 0.0;  // grid step T/64 [s]

  int mode_index(const PwlModeCode& code);
  // [E; G E; G' E; F' E] for E = e^{A T/64} of mode m, G its guards, G' their rates and F'
  // the force's rate: one product gives the state a grid step on, its guards, their slopes and
  // dF/dt there.
  const PwlGridStep& grid_step(int m);
  PwlVector advance(int m, double tau, const PwlVector& w) { return self.modes_[static_cast<std::size_t>(m)].advance(tau, w); }

  // Whether guard i of mode m is being left at state w: by its value, slope and curvature
  // (leaving()), and by its value a probe of 1e-7 T ahead where those leave it level or where
  // the curvature turns a slightly falling guard back up within the probe (a slider at the
  // drive's turning point, its slope there rounding noise of forces rates far larger).
  bool leaves(int m, int i, const PwlVector& w);

  // The mode reached from `m` with positions and velocities X and the drive's entries s, c
  // (PwlModeSystem::state_at) once every guard the state violates has switched (a stuck slider
  // above fy slips, a slipping one whose rate points against its force sticks, ...); -1 when
  // it does not settle.
  int settle(int m, const PwlVector& X, double s, double c, PwlVector& w);

  // The first time in (0, h] at which guard row i of mode m crosses from positive to
  // negative along w(tau) = e^{A tau} w0, or infinity; W_AT the state there. w1 is the state at
  // h, g0, g1 the guard's values and slope0, slope1 its slopes at 0 and h.
  double first_crossing(int m, int i, const PwlVector& w0, const PwlVector& w1, double h, double g0, double g1, double slope0, double slope1,
                        PwlVector& w_at);

  // Switches from mode m (state w, whose drive entries give the time) through guard i; with sensitivities S (dw/dX0)
  // applies the saltation matrix. Returns the new mode or -1. With TO (>= 0), into that mode
  // as it is, not settled (a replayed switch whose settled mode is known).
  int switch_at(int m, int i, PwlVector& w, PwlMatrix* S, int to = -1);

  // Follows the map's span (a period, or half of one for an odd branch) from X0, settled from
  // mode m: X at its end and, with `J`, dX/dX0; with `record`, the pieces, switch phases and
  // first harmonic. False on failure. The sensitivities are carried through each piece (from
  // its start to its switch or the span's end) at once, not per grid step
  // (PwlModeSystem::propagate).
  bool cycle(int& m, const PwlVector& X0, PwlVector& X_T, PwlMatrix* J, bool record);

  // The span's map from X0 along the sequence of switches the last recorded cycle made (its
  // pieces' modes and the guards that fired), with no grid and no other guard checked: each
  // switch time by Newton's method on its guard from the recorded one, the state between by
  // the exact flow. X at the span's end and J = dX/dX0 (through each switch by its saltation
  // matrix), for Newton's method on the map of that sequence (PwlPeriodicState::shoot). False
  // where the sequence is not kept: a crossing not found (a guard not falling through zero
  // there, a time outside the span or before the last switch) or a switch to another mode.
  // Whether the sequence holds (no other guard reached) only a followed cycle tells.
  bool replay(const PwlVector& X0, PwlVector& X_T, PwlMatrix& J);

  // K'_1 and K''_1 of the recorded cycle, its pieces' integrals int F e^{i w t} dt in modal
  // closed form. Over a half period of an odd branch the integral is half the period's (F and
  // e^{i w t} both change sign after T/2).
  void first_harmonic();

  // The periodic state of mode m followed without its guards (the linear state every point
  // starts from): the fixed point of X -> to_X e^{A T} w(X), by one propagator over the period
  // (of X -> -to_X e^{A T/2} w(X) for an odd branch: the symmetric state, whose stuck sliders
  // hold no offset, as from rest). It is proportional to the amplitude (the drive is the only
  // forcing with every slider stuck and every gap open): kept per mode at u0 = 1.
  PwlVector linear_periodic_state(int m);
};

}  // namespace rheo::runtime
