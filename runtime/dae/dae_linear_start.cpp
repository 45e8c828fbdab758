#include "runtime/dae/dae_linear_start.hpp"

#include "runtime/network/leaf_kernels.hpp"

#include <Eigen/Dense>

#include <complex>
#include <cstddef>

namespace rheo::runtime {

namespace {

using Complex = std::complex<double>;

// The edge's admittance Y (F = Y e) at angular frequency omega [rad/s]; sliders are handled as
// rigid edges by the caller.
Complex admittance(const Edge& edge, double omega) {
  switch (edge.kind) {
    case EdgeKind::spring: return edge.p[0];
    case EdgeKind::yeoh: return YeohLaw{edge.p[0], edge.p[1], edge.p[2]}.slope(0.0);
    case EdgeKind::poly_spring: return PolyLaw{edge.p[0], edge.p[1], edge.p[2]}.slope(0.0);
    case EdgeKind::dashpot: return Complex(0.0, omega * edge.p[0]);
    case EdgeKind::inerter: return -omega * omega * edge.p[0];
    case EdgeKind::quadratic_dashpot:
    case EdgeKind::bouc_wen:
    case EdgeKind::slider:
    case EdgeKind::gap: break;
  }
  return 0.0;
}

}  // namespace

std::optional<DaeLinearStart> dae_linear_periodic_start(const DaeGraph& graph, double amplitude, double omega) {
  const Eigen::Index nodes = graph.internal_nodes;
  Eigen::Index sliders = 0;
  for (const Edge& edge : graph.edges) {
    if (edge.kind == EdgeKind::gap || edge.kind == EdgeKind::quadratic_dashpot || edge.kind == EdgeKind::bouc_wen) return std::nullopt;
    if (edge.kind == EdgeKind::slider) ++sliders;
  }
  // Unknowns [X (node phasors) | L (stuck sliders' force phasors)]; rows: node balances (the
  // forces of the edges pulling each node sum to zero), then each slider's elongation phasor = 0.
  const Eigen::Index n = nodes + sliders;
  Eigen::MatrixXcd a = Eigen::MatrixXcd::Zero(n, n);
  Eigen::VectorXcd b = Eigen::VectorXcd::Zero(n);
  // A force F = Y (X_a - X_b) on the edge a -> b enters node a's balance as -F and node b's as
  // +F (DaeIntegrator::residual); the terminal's known phasor A goes to the right-hand side.
  const auto stamp = [&](int node, double sign, const Edge& edge, Complex y) {
    if (node < 0) return;
    const auto row = static_cast<Eigen::Index>(node);
    if (edge.a >= 0) a(row, edge.a) += sign * y;
    if (edge.b >= 0) a(row, edge.b) -= sign * y;
    if (edge.a == kTerminal) b(row) -= sign * y * amplitude;
    if (edge.b == kTerminal) b(row) += sign * y * amplitude;
  };
  Eigen::Index slider = nodes;
  for (const Edge& edge : graph.edges) {
    if (edge.kind == EdgeKind::slider) {
      if (edge.a >= 0) a(edge.a, slider) -= 1.0;
      if (edge.b >= 0) a(edge.b, slider) += 1.0;
      if (edge.a >= 0) a(slider, edge.a) += 1.0;
      if (edge.b >= 0) a(slider, edge.b) -= 1.0;
      if (edge.a == kTerminal) b(slider) -= amplitude;
      if (edge.b == kTerminal) b(slider) += amplitude;
      ++slider;
      continue;
    }
    const Complex y = admittance(edge, omega);
    stamp(edge.a, -1.0, edge, y);
    stamp(edge.b, 1.0, edge, y);
  }
  Eigen::VectorXcd x = Eigen::VectorXcd::Zero(n);
  if (n > 0) {
    const Eigen::FullPivLU<Eigen::MatrixXcd> lu(a);
    if (!lu.isInvertible() || lu.rcond() < 1e-12) return std::nullopt;
    x = lu.solve(b);
    if (!x.allFinite()) return std::nullopt;
  }
  const auto phasor = [&](int node) -> Complex { return node >= 0 ? x(node) : node == kTerminal ? Complex(amplitude) : Complex(0.0); };
  DaeLinearStart start;
  start.positions.resize(static_cast<std::size_t>(nodes));
  for (Eigen::Index i = 0; i < nodes; ++i) start.positions[static_cast<std::size_t>(i)] = x(i).imag();
  start.rate_edge_rates.reserve(graph.rate_edges.size());
  for (int index : graph.rate_edges) {
    const Edge& edge = graph.edges[static_cast<std::size_t>(index)];
    start.rate_edge_rates.push_back(omega * (phasor(edge.a) - phasor(edge.b)).real());
  }
  return start;
}

}  // namespace rheo::runtime
