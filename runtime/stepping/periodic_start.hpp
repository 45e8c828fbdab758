// The state a harmonic point's first cycle starts from: u = u0 sin(w t), sampled at t_k = k dt
// (n steps per cycle), so that u_k = Im(u0 z^k) with z = exp(i w dt).
//
// Every fixed-step relation that is linear is linear time-invariant in the step index, so its
// discrete periodic response to u_k is a phasor: with X the phasor of a state variable, its
// value at k = 0 is Im(X). The discrete dynamic stiffness (force phasor over elongation phasor)
// of each linear leaf follows from its step relation (leaf_kernels.hpp):
//   spring        k
//   dashpot       (c/dt) (1 - 1/z)
//   Maxwell       b (1 - 1/z) / (1 - a/z)            (exact update, eq. 2.7: F <- a F + b de)
//   inerter       (4 b/dt^2) ((1 - 1/z)/(1 + 1/z))^2  (Newmark: Tustin's map of b s^2),
//                 velocity phasor (2/dt) (1 - 1/z)/(1 + 1/z) E
// and blocks compose as the step relations do: parallel K = sum K_i (common E), series
// K = 1 / sum(1/K_i) (common F, E_i = F/K_i).
//
// Root Maxwell elements start at their discrete periodic state; root friction elements and
// sliders at the force they reach on the first loading. A subtree starts at the discrete
// periodic state of its linearisation with sliders stuck (rigid members of their chains),
// friction elements within their caps (springs k) and yeoh springs at their slope at rest
// (2 D10), if every cap holds at that state's force amplitude: without yeoh springs the first
// cycle is then periodic up to rounding, with them it starts near the periodic state. Otherwise (a cap slips), and for
// subtrees with a gap, bouc_wen or quadratic dashpot, or a block that is rigid while its sliders
// stick, the subtree starts at rest (measured on the hydrobushing grid: a clamped linear start
// takes more cycles than rest where the cap slips).
#pragma once

#include "runtime/network/network.hpp"
#include "runtime/stepping/simulator.hpp"

namespace rheo::runtime {

// With PRELOAD p != 0 (u = p + u0 sin(w t)) the root elements start as above (they see only the
// drive's increments) and the subtrees keep the state they were given (the relaxed state at p:
// their linearisation about p is not formed here).
void set_periodic_start(const Network& network, const StepPlan& plan, double amplitude, int steps, State& state, double preload = 0.0);

}  // namespace rheo::runtime
