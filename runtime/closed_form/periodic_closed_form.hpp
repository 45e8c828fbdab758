// Periodic steady state of a harmonic test u = u0 sin(theta), theta = w t, in closed form, for
// networks whose non-linear elements all sit in the root parallel block (the thesis models,
// Figs. 2.5, 5.1, 5.3, with any linear sub-networks beside them): no transient is simulated
// and no time step is involved.
//
// Branch forces over one steady cycle, loading half theta in [-pi/2, pi/2] (u rising):
//   spring k             F = k u
//   yeoh D10, D20, D30   F = Y(u) = 2 D10 u + 4 D20 u^3 + 6 D30 u^5                    (eq. 3.3)
//   dashpot c            F = c w u0 cos(theta)                                         (B.39)
//   Maxwell k, tau       F = u0 (K' sin(theta) + K'' cos(theta)),
//                        K' = k w^2 tau^2 / (1 + w^2 tau^2), K'' = k w tau / (1 + w^2 tau^2)  (5.11, B.58)
//   friction k, fy       u0 <= uy = fy/k: F = k u (elastic; the state reached from rest);
//                        u0 > uy: F = min(fy, -fy + k (u + u0)) (Masing loop, C.2.1)
//   slider fy            F = fy (rigid-plastic, B.25)
//   poly_spring k1, k2, k3   F = k1 u + k2 u^2 + k3 u^3: odd part k1 u + k3 u^3 (K' = k1 + (3/4) k3 u0^2),
//                        even part k2 u^2 (nothing to K*_1 and U; F^ = (max F - min F)/2 as for a preload)
//   friction, slider with one-sided yield forces fy_pos, fy_neg (a root-block leaf): shaken down
//                        from rest, the steady cycle is that of fy = (fy_pos + fy_neg)/2 plus the
//                        constant (fy_pos - fy_neg)/2 (loading min(fy_pos, -fy_neg + k (u + u0)) =
//                        c + min(fy, -fy + k (u + u0))), which no measure sees: K*_1, U and
//                        max F - min F are those of the mean yield force
//   linear subtree       F = u0 (K' sin(theta) + K'' cos(theta)), K* = K' + i K'' composed from
//                        spring k, dashpot i w c, Maxwell k i w tau / (1 + i w tau), inerter
//                        -b w^2 (springpot chains are Maxwell elements), parallel: sum K*,
//                        series: 1 / sum (1 / K*)                                 (eq. 2.1, C.9)
// and the unloading half is the mirror image, F(theta + pi) = -F(theta), so that
// max F = -min F and F^ = max over the loading half.
//
// Dissipated energy per cycle (exact, additive over branches):
//   U = pi u0^2 (sum K'' + c w) + sum_{u0 > uy} 4 fy (u0 - uy) + sum_sliders 4 fy u0     (5.17, C.2)
// First harmonic K*_1 = K' + i K'' (additive over branches):
//   yeoh      K' = 2 D10 + 3 D20 u0^2 + (15/4) D30 u0^4  (from sin^3, sin^5 expansions)
//   friction  K' = (k/pi) (theta* + pi/2 + s* cos theta*), s* = sin theta* = 2 uy/u0 - 1,
//             K'' = 4 fy (u0 - uy) / (pi u0^2)            (u0 > uy; else K' = k)
//   slider    K'' = 4 fy / (pi u0)
//
// F^ = u0 |K*| where every branch is linear (the force is a u0-scaled sinusoid, K'' >= 0); else
// F^ = max of the loading-half force: the force is smooth between the friction slip points
// theta_q = asin(2 uy_q/u0 - 1), so each piece is searched for the sign changes of dF/dtheta
// on a sampling of at least 32 points per half cycle, each root polished by safeguarded
// Newton to machine precision; piece ends are candidates too. (Two maxima closer than the
// sampling could be missed; no element law here produces them.) Where every branch's in-phase
// stiffness is non-negative over |u| <= u0 (always, unless a yeoh spring softens below zero
// slope) dF/dtheta >= 0 on [-pi/2, 0], and only [0, pi/2] is searched.
//
// The result is the continuous-time steady state the time-stepping path converges to as
// the step shrinks (error O(1/N^2) there), hence the "exact" evaluation used by fitting.
#pragma once

#include "runtime/core/harmonic_point.hpp"
#include "runtime/network/network.hpp"

#include <optional>

namespace rheo::runtime {

// True when every subtree (nested block, or inerter leaf) is linear (springs, dashpots, Maxwell
// elements, springpot chains and inerters only), a root-block poly_spring or one-sided friction
// element or slider (above), or piecewise linear with an event-driven
// periodic state (pwl_branch.hpp: those and friction elements, sliders and gaps, also with
// one-sided caps and off-centre; F^ = (max F - min F)/2 over the whole cycle for those) unless
// `event_driven` is false.
bool has_closed_form_periodic_state(const Network& network, bool event_driven = true);

// Requires has_closed_form_periodic_state(network), amplitude > 0 [mm], frequency > 0 [Hz].
// Nothing when a piecewise-linear subtree's periodic state does not settle
// (PwlPeriodicState::solve), or when a preload meets a gap in one (its play is fixed in space):
// the caller time-steps the point.
// PRELOAD p [mm]: the drive is u = p + u0 sin(theta) from the relaxed state at p. Every branch
// but the yeoh springs is shift-invariant (its periodic force moves by a constant); a yeoh
// spring about p is Y(p + u) - Y(p) = y1 u + y2 u^2 + y3 u^3 + y4 u^4 + y5 u^5 with
//   y1 = 2 D10 + 12 D20 p^2 + 30 D30 p^4 (its tangent stiffness at p), y2 = 12 D20 p + 60 D30 p^3,
//   y3 = 4 D20 + 60 D30 p^2, y4 = 30 D30 p, y5 = 6 D30;
// the odd part adds K' = y1 + (3/4) y3 u0^2 + (5/8) y5 u0^4 to K*_1 and the even part nothing to
// K*_1 and U, but breaks the mirror symmetry: F^ = (max F - min F)/2 with min F searched on the
// mirrored half.
// PEAK_PHASE, where given, receives the phase theta in [-pi/2, pi/2] of the loading half where
// F^ = max F is reached when the cycle is half-wave symmetric (F^ = max F = -min F), NaN
// otherwise (closed_form_sensitivity.hpp differentiates F^ there).
std::optional<HarmonicPoint> try_closed_form_harmonic_point(const Network& network, double amplitude, double frequency,
                                                            HarmonicDefinition definition, double preload = 0.0, double* peak_phase = nullptr);
// The same, with a NumericalError where that returns nothing.
HarmonicPoint closed_form_harmonic_point(const Network& network, double amplitude, double frequency, HarmonicDefinition definition,
                                         double preload = 0.0);

}  // namespace rheo::runtime
