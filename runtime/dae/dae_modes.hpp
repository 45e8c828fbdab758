// Kinematics of one switching mode of a DaeGraph: which rate coordinates are independent.
//
// A mode fixes every slider (stuck, slipping +, slipping -) and gap (open, closed +, closed -).
// Stuck sliders and closed gaps are rigid: their elongation is held, R x + r u = const. The
// rates of the rate edges (dashpots, quadratic dashpots, inerters), e_r' = D_r x' + d_r u', then
// span a space of dimension q <= their number. A basis of q of them is chosen as the
// differential coordinates s_j of the DAE (inerters first, so that every inerter's acceleration
// is a combination of the velocities w_j = s_j' of inerter coordinates), and every rate edge is
//   e_r' = sum_j alpha_rj s_j' + beta_r u'                           (exact, linear algebra)
// with e_r'' = sum_j alpha_rj w_j' + beta_r u'' for inerters. This choice keeps the DAE index 1
// in every mode (node positions are algebraic: the balance of a node without rate edges fixes
// it), which IDA needs. A rate edge whose row vanishes in the mode is driven: e_r' = beta_r u'.
#pragma once

#include "runtime/dae/dae_graph.hpp"

#include <cstdint>
#include <vector>

namespace rheo::runtime {

// Per switch edge (DaeGraph::switch_edges order): slider 0 stuck, +1/-1 slipping in that
// direction; gap 0 open, +1/-1 closed at e = +-w/2.
using SwitchModes = std::vector<std::int8_t>;

bool is_rigid(const Edge& edge, std::int8_t mode);

struct ModeKinematics {
  int coordinates = 0;               // q
  std::vector<int> coordinate_rate;  // [q] index into DaeGraph::rate_edges of each coordinate
  std::vector<int> velocity_slot;    // [q] slot of w_j for inerter coordinates, -1 otherwise
  std::vector<double> alpha;         // [rate_edges x q], row-major
  std::vector<double> beta;          // [rate_edges]

  // Throws NumericalError (naming the inerter) when an inerter is held rigidly to the drive in
  // this mode, which would need the drive's acceleration as an impulse.
  static ModeKinematics make(const DaeGraph& graph, const SwitchModes& modes);
};

}  // namespace rheo::runtime
