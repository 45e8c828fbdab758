// Where a harmonic point on the variable-step (IDA) backend starts: the periodic state of the
// network's linearisation under u = A sin(w t), at t = 0.
//
// Started from rest, a network reaches its periodic state only as fast as its slowest mode
// decays: a springpot's chain has a tail mode of thousands of seconds, an undamped mass never
// settles. Linearised (sliders stuck, yeoh and polynomial springs at their tangent at rest), every
// edge is an admittance Y (F = Y e with e the elongation's phasor, u = Im(A e^{iwt})):
//   spring k;  yeoh 2 D10 (eq. 3.3 at e = 0);  poly_spring k1;  dashpot i w c;  inerter -w^2 b,
// and a stuck slider holds its elongation (a rigid edge whose force is an unknown). The node
// balances and the rigid edges are one complex linear system in the internal nodes' phasors X and
// the sliders' force phasors. At t = 0 the state is x = Im(X) and every rate edge's elongation
// rate e' = Im(i w E) = w Re(E); for a linear network this is the periodic state itself (a
// harmonic point then converges in its first cycles), for others a start near it.
//
// The fixed-step kernels start from the discrete counterpart of this state (numerics.md,
// "Harmonic steady state").
#pragma once

#include "runtime/dae/dae_graph.hpp"

#include <optional>
#include <vector>

namespace rheo::runtime {

struct DaeLinearStart {
  std::vector<double> positions;        // [internal_nodes] mm, at t = 0
  std::vector<double> rate_edge_rates;  // [DaeGraph::rate_edges] mm/s, the rate of each one's elongation
};

// None where the linearisation does not serve: a gap, a quadratic dashpot (no tangent at rest)
// or a bouc_wen in the graph, or a singular system (a node that no admittance holds).
std::optional<DaeLinearStart> dae_linear_periodic_start(const DaeGraph& graph, double amplitude, double omega);

}  // namespace rheo::runtime
