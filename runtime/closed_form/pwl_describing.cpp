#include "runtime/closed_form/pwl_describing.hpp"

#include <cmath>
#include <complex>
#include <numbers>

namespace rheo::runtime {
namespace {

using Complex = std::complex<double>;
constexpr int kMax = kPwlMaxDim + 1;  // the internal nodes and the slider's multiplier
using ComplexMatrix = Eigen::Matrix<Complex, Eigen::Dynamic, Eigen::Dynamic, 0, kMax, kMax>;
using ComplexPair = Eigen::Matrix<Complex, Eigen::Dynamic, 2, 0, kMax, 2>;

// The first harmonic s^ = S_sin + i S_cos of the periodic slip of a Jenkins element (a spring
// and a slider of yield displacement y in series) driven by v = a sin(theta), 0 < y < a: from
// the turning point theta = -pi/2 (s = y - a) stuck until v = 2 y - a at theta_1, then
// slipping, s = v - y, to s = a - y at pi/2; the other half mirrored, s(theta + pi) = -s(theta).
// S_sin = (2/pi) int_{-pi/2}^{pi/2} s sin, S_cos likewise with cos, in closed form.
Complex jenkins_slip(double a, double y) {
  const double sin1 = 2.0 * y / a - 1.0, cos1 = std::sqrt(std::max(0.0, 1.0 - sin1 * sin1)), theta1 = std::asin(sin1);
  const double held = y - a;  // the stuck offset from -pi/2 to theta_1
  const double stuck_sin = -held * cos1, stuck_cos = held * (sin1 + 1.0);
  const double slip_sin = a * (0.25 * std::numbers::pi - 0.5 * theta1 + 0.5 * sin1 * cos1) - y * cos1;
  const double slip_cos = 0.5 * a * cos1 * cos1 - y * (1.0 - sin1);
  return (2.0 / std::numbers::pi) * Complex(stuck_sin + slip_sin, stuck_cos + slip_cos);
}

// Gaussian elimination with partial pivoting, in place (a few unknowns: Eigen's decompositions
// cost more in their setup than the elimination); false where a pivot is below 1e-13 of the
// largest entry (the slider's constraint would leave the branch indeterminate).
bool solve_small(ComplexMatrix& m, ComplexPair& rhs, ComplexPair& out) {
  const Eigen::Index size = m.rows();
  const double largest = m.cwiseAbs().maxCoeff();
  for (Eigen::Index c = 0; c < size; ++c) {
    Eigen::Index pivot = c;
    for (Eigen::Index r = c + 1; r < size; ++r)
      if (std::abs(m(r, c)) > std::abs(m(pivot, c))) pivot = r;
    if (!(std::abs(m(pivot, c)) > 1e-13 * largest)) return false;
    m.row(c).swap(m.row(pivot)), rhs.row(c).swap(rhs.row(pivot));
    for (Eigen::Index r = c + 1; r < size; ++r) {
      const Complex factor = m(r, c) / m(c, c);
      m.row(r).tail(size - c) -= factor * m.row(c).tail(size - c);
      rhs.row(r) -= factor * rhs.row(c);
    }
  }
  out.resize(size, 2);
  for (Eigen::Index r = size - 1; r >= 0; --r) {
    Eigen::Matrix<Complex, 1, 2> sum = rhs.row(r);
    for (Eigen::Index c = r + 1; c < size; ++c) sum -= m(r, c) * out.row(c);
    out.row(r) = sum / m(r, r);
  }
  return true;
}

}  // namespace

bool pwl_describing_start(const PwlBranch& branch, double u0, double omega, PwlVector& X0) {
  const int n = branch.internal_nodes;
  if (!branch.odd || branch.switches.size() != 1 || n < 1 || n + 1 > kMax) return false;
  const PwlEdge& slider = branch.edges[static_cast<std::size_t>(branch.switches.front())];
  if (slider.kind != PwlEdgeKind::slider || slider.cap_neg != slider.value) return false;
  // Kept per thread: constructing a fixed-capacity complex matrix clears its whole capacity
  // (std::complex constructs every entry), some 10 kB, more than the rest of the estimate.
  thread_local ComplexMatrix system;
  thread_local ComplexPair rhs, solution;
  // Right-hand sides per unit drive u^ (column 0) and per unit elongation e^ of the slider (1).
  system.setZero(n + 1, n + 1), rhs.setZero(n + 1, 2);
  auto internal = [&](int node) { return node >= 0; };
  for (const PwlEdge& edge : branch.edges) {
    if (&edge == &slider) continue;
    Complex y;  // the edge's dynamic stiffness [N/mm]
    switch (edge.kind) {
      case PwlEdgeKind::spring: y = edge.value; break;
      case PwlEdgeKind::dashpot: y = Complex(0.0, omega * edge.value); break;
      case PwlEdgeKind::inerter: y = -omega * omega * edge.value; break;
      default: return false;  // a gap: no estimate
    }
    if (internal(edge.a)) system(edge.a, edge.a) += y;
    if (internal(edge.b)) system(edge.b, edge.b) += y;
    if (internal(edge.a) && internal(edge.b)) system(edge.a, edge.b) -= y, system(edge.b, edge.a) -= y;
    if (internal(edge.a) && edge.b == kPwlTerminal) rhs(edge.a, 0) += y;
    if (internal(edge.b) && edge.a == kPwlTerminal) rhs(edge.b, 0) += y;
  }
  // The slider: K x + r F = f u, r^T x = e - rho u (e = x_a - x_b, F its tension).
  double rho = 0.0;
  if (internal(slider.a)) system(slider.a, n) = system(n, slider.a) = 1.0;
  if (internal(slider.b)) system(slider.b, n) = system(n, slider.b) = -1.0;
  if (slider.a == kPwlTerminal) rho = 1.0;
  if (slider.b == kPwlTerminal) rho = -1.0;
  rhs(n, 0) = -rho, rhs(n, 1) = 1.0;
  if (!solve_small(system, rhs, solution)) return false;
  const Complex stuck_force = u0 * solution(n, 0), Z = -solution(n, 1);
  const double k = std::abs(Z), fy = slider.value;
  if (!(k > 0.0) || !(std::abs(stuck_force) > fy) || !std::isfinite(std::abs(stuck_force))) return false;
  const Complex v = stuck_force / Z;  // the Jenkins element's drive, v^ = F_stuck / Z
  const double a = std::abs(v);
  const Complex slip = jenkins_slip(a, fy / k) * (v / a);  // back from v's phase to the drive's
  X0.resize(2 * n);
  for (int j = 0; j < n; ++j) {
    const Complex x = u0 * solution(j, 0) + slip * solution(j, 1);
    X0[j] = x.imag(), X0[n + j] = omega * x.real();
  }
  return X0.allFinite();
}

}  // namespace rheo::runtime
