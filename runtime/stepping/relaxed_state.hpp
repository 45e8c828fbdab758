// The relaxed start of a displacement history (#25 item 1; docs/numerics.md "Relaxed start"):
// the state of a specimen held at the first sample's displacement u0 until everything that can
// relax has, as a rig that held the specimen before the test delivers it.
//
// Every element that carries no force at rest at any elongation is "free": dashpots, quadratic
// dashpots, Maxwell elements (and so springpot modes), inerters (rate zero); friction elements,
// sliders and bouc_wen elements, slid to zero force. Springs (F = k e) and yeoh springs
// (eq. 3.3) carry their static force; a gap carries none within its play |e| <= w/2 and is
// rigid at its stops. Static equilibrium then fixes every elongation that carries force:
//   parallel: common elongation e, F = sum_i F_i(e);
//   series:   common force F,      e = sum_i e_i(F).
// A chain with a free member carries F = 0: its other members sit at their zero-force
// elongation (springs and yeoh springs 0, gaps centred) and its first free member takes the
// rest. A chain without one takes F = 0 while e lies within its members' play (gaps filled in
// order) and is solved for F on the side e lies on otherwise.
//
// At u0 = 0 every value is exactly 0: the rest state (Simulator::rest_state), so a history
// from displacement 0 gives the same results either way.
#pragma once

#include "runtime/core/drive.hpp"
#include "runtime/network/network.hpp"
#include "runtime/stepping/simulator.hpp"

namespace rheo::runtime {

// The relaxed state at drive displacement u0 [mm] in the Simulator's State layout: every tree
// node's (e, F) from the equilibrium above, its other slots (rates) 0; root Maxwell, friction
// and slider forces 0; State::u = u0, State::force the terminal force [N].
// ModelError where a yeoh spring in a chain would have to carry more than its softening law can.
State relaxed_state(const Network& network, double u0);
// The relaxed state's terminal force and every element's force and elongation (probes order).
StartAtRest relaxed_start(const Network& network, const State& relaxed);

}  // namespace rheo::runtime
