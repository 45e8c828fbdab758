// A branch of the model's parallel body (a subtree) as a piecewise-linear graph, for the
// event-driven periodic state (pwl_periodic.hpp).
//
// The branch is driven by the terminal, x_T = u(t), and held by ground, x_G = 0; every
// junction of a series chain is an internal node j with position x_j [mm]. Each leaf becomes
// one or two edges from node a to node b with elongation e = x_a - x_b [mm] and tension F [N]:
//   spring k [N/mm]          F = k e
//   dashpot c [N*s/mm]       F = c de/dt
//   inerter b [N*s^2/mm]     F = b d2e/dt2
//   slider fy+, fy- [N]      -fy- <= F <= fy+; rigid (de/dt = 0) inside, F = fy+ while it slips
//                            with de/dt > 0, F = -fy- with de/dt < 0 (fy+ = fy- = fy: one cap both ways)
//   gap w, c [mm]            F = 0 while |e - c| < w/2; rigid at e = c + w/2 while it pulls
//                            (F >= 0) and at e = c - w/2 while it pushes (F <= 0)
//   maxwell (k, c)           spring k + dashpot c through a new node (eq. 2.3)
//   friction (k, fy+, fy-)   spring k + slider (fy+, fy-) through a new node (eq. 2.9)
// Between switches of its sliders and gaps every such branch is linear (docs/numerics.md).
#pragma once

#include "runtime/network/network.hpp"

#include <cstdint>
#include <vector>

namespace rheo::runtime {

enum class PwlEdgeKind : std::uint8_t { spring, dashpot, inerter, slider, gap };

// The capacity of the event path's fixed-size storage (pwl_mode.hpp): the augmented state of a
// mode, 2 N + (rigid edges) + 3 entries for N internal nodes, and its guard rows, two per
// slider or gap, stay within it.
inline constexpr int kPwlMaxDim = 24;

inline constexpr int kPwlTerminal = -1;  // node index of the driven terminal
inline constexpr int kPwlGround = -2;    // node index of ground

struct PwlEdge {
  PwlEdgeKind kind = PwlEdgeKind::spring;
  int a = kPwlTerminal, b = kPwlGround;
  double value = 0.0;    // k, c, b, a slider's cap in tension fy+ [N], or a gap's half width w/2 [mm]
  double cap_neg = 0.0;  // a slider's cap in compression fy- [N] (fy+ for one cap both ways)
  double center = 0.0;   // a gap's centre c [mm]

  // The force of a slider slipping in direction `sign` (+1: de/dt > 0, F = fy+; -1: F = -fy-).
  double slip_force(int sign) const { return sign > 0 ? value : -cap_neg; }
};

struct PwlBranch {
  int internal_nodes = 0;
  std::vector<PwlEdge> edges;
  std::vector<int> switches;  // indices of slider and gap edges
  // Every edge law is odd (F(-e, -de/dt) = -F(e, de/dt): sliders with one cap both ways, gaps
  // centred on e = 0). Then under u0 sin(w t) the mirrored state half a period later is again
  // a solution, and the periodic state is found on the half-period map (pwl_periodic.hpp).
  // False where a slider or friction element has separate caps fy_pos, fy_neg (their values
  // aside: a fit may move them apart) or a gap a centre written other than 0 or fitted: the
  // periodic state is then found on the full-period map.
  bool odd = true;

  // The graph of subtree `root` of `network` (a node index of Topology::subtrees), or nothing
  // when the subtree is not piecewise linear (a yeoh, poly_spring, quadratic_dashpot or bouc_wen
  // below it), is linear (no slider, friction or gap: the phasor path serves it), or could lose its
  // determinacy in some mode: sliders and gaps that close a loop, or a path from the terminal
  // to ground, when rigid (their forces would not be fixed by the network), or is too large
  // for kPwlMaxDim (more than about ten internal nodes: it time-steps).
  static bool build(const Network& network, int root, PwlBranch& out);
};

}  // namespace rheo::runtime
