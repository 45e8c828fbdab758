// The network as a graph of two-terminal edges between nodes, for the variable-step
// (SUNDIALS IDA) backend.
//
// Node positions x [mm] are the unknowns: the driven terminal follows u(t), ground is 0 and
// every junction inside a series chain is an internal node. An edge from node a to node b has
// elongation e = x_a - x_b and a tension force F (the force the rig measures at the terminal
// is the sum of the forces of the edges leaving it). Composite leaves are expanded into their
// physical parts, so every edge has one simple constitutive law:
//   spring     F = k e                        yeoh       F = 2 (D10 + 2 D20 e^2 + 3 D30 e^4) e (eq. 3.3)
//   dashpot    F = c de/dt                    quadratic  F = cq de/dt sqrt((de/dt)^2 + v_eps^2)
//   inerter    F = b d2e/dt2                  bouc_wen   F = fy z, dz/dt = (k/fy) de/dt (1 - |z|^n (1 + sgn(z de/dt))/2)
//   slider     -fy_neg <= F <= fy_pos, sticks inside     gap  F = 0 for |e - c| < w/2, rigid at e = c +- w/2
//   poly_spring F = k1 e + k2 e^2 + k3 e^3
//   maxwell(k, c)  -> spring k + dashpot c through a new node (eq. 2.3)
//   friction(k, fy) -> spring k + slider fy through a new node (eq. 2.9)
//   springpot       -> its Maxwell chain (runtime/network/springpot.hpp), each mode as a maxwell
// v_eps regularises the quadratic dashpot at rest (its tangent c_q |v| vanishes there, which
// would make the Newton matrix singular); the force error is below (v_eps/v)^2/2 relative.
//
// Built once per parameter set; immutable.
#pragma once

#include "runtime/network/network.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace rheo::runtime {

enum class EdgeKind : std::uint8_t { spring, yeoh, poly_spring, dashpot, quadratic_dashpot, inerter, bouc_wen, slider, gap };

inline constexpr int kTerminal = -1;                          // node index of the driven terminal
inline constexpr int kGround = -2;                            // node index of ground
inline constexpr double kQuadraticDashpotVelocityEps = 1e-3;  // v_eps [mm/s]

struct Edge {
  EdgeKind kind = EdgeKind::spring;
  int a = kTerminal, b = kGround;  // e = x_a - x_b
  double p[3] = {0.0, 0.0, 0.0};   // spring {k}, yeoh {D10, D20, D30}, poly_spring {k1, k2, k3}, dashpot {c},
                                   // quadratic {cq}, inerter {b}, bouc_wen {k, n, fy},
                                   // slider {fy_pos, fy_neg} (both fy when symmetric), gap {w/2, center}
  std::string path;                // the user's element this edge belongs to
  lang::SourceLocation where;      // where that element is written
};

// Edges that make up one element the user wrote (Topology::probes order): the element's
// elongation is the sum of the elongations of `edges` (a path from its first terminal to its
// second), its force the sum of the forces of `force_edges` (the first edge of a series
// expansion; the springs of every mode of a springpot's Maxwell chain).
struct EdgeProbe {
  std::string path;
  std::vector<int> edges;
  std::vector<int> force_edges;
};

struct DaeGraph {
  int internal_nodes = 0;
  std::vector<Edge> edges;
  std::vector<EdgeProbe> probes;
  std::vector<int> rate_edges;      // dashpot, quadratic dashpot, inerter: their rate is a coordinate
  std::vector<int> switch_edges;    // sliders and gaps: their force is an unknown of the mode
  std::vector<int> bouc_wen_edges;  // each carries the state z
  std::string model;

  // Throws ModelError with advice when the network cannot be posed as an index-1
  // DAE: an internal node held only by sliders and gaps, an inerter, slider or gap directly
  // between terminal and ground, a bouc_wen between internal nodes in a network with sliders
  // or gaps (friction elements included; docs/errors.md lists these rules).
  static DaeGraph build(const Network& network);
};

// The largest force [N] a spring-like edge (spring, yeoh's linear term, poly_spring's k1)
// carries at elongation LENGTH [mm]: the size of the terms a position's rounding is multiplied
// by in the node balances.
double stiffest_spring_force(const DaeGraph& graph, double length);

// Internal node positions [mm] of a configuration at rest with the terminal at u0 [mm], from
// the force [N] and elongation [mm] of every element the user wrote (probes order): the spring
// of a Maxwell or friction element carries its force (e = F/k), its dashpot or slider the rest
// of its elongation; a springpot's modes carry none (relaxed), their dashpots its elongation.
std::vector<double> positions_at_rest(const DaeGraph& graph, double u0, const std::vector<double>& force, const std::vector<double>& elongation);

}  // namespace rheo::runtime
