// One mode of a piecewise-linear branch (pwl_branch.hpp) under the drive u = u0 sin(w t): every
// slider stuck or slipping, every gap open or closed. In a mode the branch is a linear system
// with constant coefficients, written as the augmented linear ODE
//   w' = A w,   w = (z, h, 1, s, c),   s = u0 sin(w t), c = u0 cos(w t)   (s' = w c, c' = -w s),
// which its matrix exponential solves exactly: w(t + tau) = e^{A tau} w(t). The amplitude is
// carried by the drive's entries of w, so A (and everything built from it) depends on the
// frequency only: one build of a mode serves every amplitude of a frequency.
//
// Derivation (node positions x [mm] of the internal nodes, N of them): edge laws in node
// equilibrium give the second-order system
//   M x'' + C x' + K x = -(k_T u + c_T u' + m_T u'') - f_slip - R^T lambda,
// M, C, K the inerter, dashpot and spring Laplacians over the internal nodes (symmetric,
// positive semi-definite), k_T, c_T, m_T their couplings to the terminal, f_slip the fy+ or -fy- of
// slipping sliders, and for the rigid edges (stuck sliders, closed gaps) the constraints
// R x + rho u = h with their held elongations h and unknown tensions lambda. With
// x = R^+ (h - rho u) + N y (N an orthonormal basis of ker R) and the projection onto N the
// tensions drop out. In y the mass matrix splits the space into massive directions
// (coordinates eta_m and their rates v_m), massless damped ones (eta_d, first order) and
// massless undamped ones (eta_a, algebraic: solved by static condensation, which needs their
// stiffness to be positive definite: otherwise the mode is indeterminate and refused). The
// state is z = (eta_d, eta_m, v_m); h is constant within the mode.
//
// Every quantity the branch needs is then a linear functional of w: node positions and
// velocities X = (x, x') = to_X w, the tensions lambda (from the full equilibrium with
// x'' = to_X-part A^2 w), the terminal force F = force w, and the guards: rows of
// `guards` w that stay >= 0 while the mode holds (a stuck slider's fy+ - lambda and
// lambda + fy-, a slipping slider's sgn * rate, an open gap's c + w/2 - e and e - c + w/2, a
// closed gap's sgn * lambda).
#pragma once

#include "runtime/closed_form/pwl_branch.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <complex>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace rheo::runtime {

// The event path's storage has a fixed capacity (kPwlMaxDim, pwl_branch.hpp), so following a
// cycle never touches the heap.
using PwlVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kPwlMaxDim, 1>;
using PwlRow = Eigen::Matrix<double, 1, Eigen::Dynamic, Eigen::RowMajor, 1, kPwlMaxDim>;
using PwlMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kPwlMaxDim, kPwlMaxDim>;
using PwlComplexVector = Eigen::Matrix<std::complex<double>, Eigen::Dynamic, 1, 0, kPwlMaxDim, 1>;
using PwlComplexRow = Eigen::Matrix<std::complex<double>, 1, Eigen::Dynamic, Eigen::RowMajor, 1, kPwlMaxDim>;
using PwlComplexMatrix = Eigen::Matrix<std::complex<double>, Eigen::Dynamic, Eigen::Dynamic, 0, kPwlMaxDim, kPwlMaxDim>;

// OUT = A B (OUT neither A nor B), column by column as sums of A's columns in the order of
// k: for the event path's small matrices, without the size dispatch of a general product.
// INNER > 0 is A's column count known to the compiler (the sum unrolled), 0 any.
template <int Inner>
void multiply_columns(const PwlMatrix& a, const PwlMatrix& b, PwlMatrix& out) {
  const Eigen::Index rows = a.rows(), inner = Inner > 0 ? Inner : a.cols(), cols = b.cols();
  out.resize(rows, cols);
  const double* from = a.data();  // column k at from + k rows
  for (Eigen::Index c = 0; c < cols; ++c) {
    double* column = out.col(c).data();
    const double* factor = b.col(c).data();
    for (Eigen::Index r = 0; r < rows; ++r) {
      double sum = 0.0;
      for (Eigen::Index k = 0; k < inner; ++k) sum += from[k * rows + r] * factor[k];
      column[r] = sum;
    }
  }
}

// Calls f(std::integral_constant<int, n>) where n (a state's size, or A's column count) is 4 to
// 8, the sizes of the usual branches (a slider-capped column: 5 and 6), f(integral_constant<int, 0>) otherwise.
template <class F>
void with_small_size(Eigen::Index n, F&& f) {
  switch (n) {
    case 4: f(std::integral_constant<int, 4>{}); break;
    case 5: f(std::integral_constant<int, 5>{}); break;
    case 6: f(std::integral_constant<int, 6>{}); break;
    case 7: f(std::integral_constant<int, 7>{}); break;
    case 8: f(std::integral_constant<int, 8>{}); break;
    default: f(std::integral_constant<int, 0>{}); break;
  }
}

inline void multiply(const PwlMatrix& a, const PwlMatrix& b, PwlMatrix& out) {
  with_small_size(a.cols(), [&](auto inner) { multiply_columns<decltype(inner)::value>(a, b, out); });
}

// OUT = M v (v the first M.cols() entries of V) for a column-major matrix M of the event path's storage: where its column count
// (a state's size, 4 to 8 for the usual branches) is small, at that size known to the
// compiler (the columns unrolled), else as a general lazy product.
template <int Columns, class Matrix, class Vector, class Out>
void multiply_fixed(const Matrix& m, const Vector& v, Out& out) {
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Columns>> fixed(m.data(), m.rows(), Columns);
  const Eigen::Matrix<double, Columns, 1> x = v.template head<Columns>();
  out.resize(m.rows());
  out.noalias() = fixed.lazyProduct(x);
}

template <class Matrix, class Vector, class Out>
void multiply(const Matrix& m, const Vector& v, Out& out) {
  with_small_size(m.cols(), [&](auto columns) {
    if constexpr (decltype(columns)::value > 0) multiply_fixed<decltype(columns)::value>(m, v, out);
    else out.noalias() = m.lazyProduct(v.head(m.cols()));
  });
}

// One entry per PwlBranch::switches: slider 0 stuck, +1 / -1 slipping with F = fy+ / -fy- (de/dt
// of that sign); gap 0 open, +1 / -1 closed at e = c + w/2 / c - w/2.
using PwlModeCode = std::vector<std::int8_t>;

// What a guard row leads to when it reaches zero: switch `which` (an index into
// PwlBranch::switches) takes state `to`.
struct PwlTransition {
  int which = 0;
  std::int8_t to = 0;
  // The size of the guarded quantity (N, mm or mm/s), for tolerances: max(scale, per_amplitude u0).
  double scale = 1.0, per_amplitude = 0.0;
  double size(double u0) const { return std::max(scale, per_amplitude * u0); }
};

// Per modal coordinate j of a mode: 2 for the first of a conjugate pair (lambda_{j+1} =
// conj(lambda_j), V's column j + 1 and V^-1's row j + 1 the conjugates of j's), 0 for the
// second, 1 for a real eigenvalue. A real state's modal coordinates are then q_{j+1} =
// conj(q_j) at every time, and a real quantity sum_j Re(V_ij q_j) is the sum of weight_j
// Re(V_ij q_j): the flows form only the first of each pair.
using PwlModalWeights = std::array<std::int8_t, kPwlMaxDim>;

// What building a mode computes that depends on neither the amplitude nor the frequency (only
// the drive's columns of w do): the constraint split x = P (h - rho u) + N y, the massive,
// damped and algebraic directions with their inverted blocks, and the modal decomposition of
// the state block A_zz. The first build of a mode fills it; builds of the same branch and code
// at other drives reuse it (a harmonic grid builds each mode once instead of once per point).
struct PwlModeStructure {
  bool filled = false;
  bool determinate = true;  // false: the mode is indeterminate (build_pwl_mode returns false)
  PwlMatrix P, N, Vm, Vd, Va;
  PwlMatrix Kaa_inverse, Cdd_inverse, Mmm_inverse;
  // The build's products that do not involve the drive's columns (pwl_mode.cpp names them as its
  // equations do), kept so that a build at another frequency forms only the rest: the same
  // expressions of the same operands, so a mode is the same to the last bit whichever frequency
  // filled its structure.
  PwlMatrix K, C, M;                                      // n x n Laplacians
  PwlVector kT, cT, mT, f_slip;                           // n: terminal couplings, slip forces
  PwlMatrix R;                                            // r x n
  PwlVector rho, P_rho;                                   // r, n
  PwlVector drive_k, drive_m, drive_c;                    // K P rho - k_T, M P rho - m_T, C P rho - c_T
  PwlMatrix Kq, Cq, Fy_held;                              // N^T K N, N^T C N, -N^T K P
  PwlVector Fy_one;                                       // -N^T f_slip
  PwlMatrix Sd, Sm, Sv, Vd_Sd, Vm_Sm, Vm_Sv;              // selections of w and their images in y
  PwlMatrix condensed, damped_coupling, Vm_Cq, tensions;  // Va^T Kq (Vd Sd + Vm Sm), Vd^T Cq Vm Sv, Vm^T Cq, -(R R^T)^-1 R
  PwlMatrix from_X;
  std::vector<PwlVector> incidence;  // per edge: e = incidence . x + terminal u
  std::vector<double> terminal;
  std::array<int, kPwlMaxDim> rigid{};  // edge indices of stuck sliders and closed gaps, in switch order
  int r = 0, guard_count = 0;
  double largest_k = 0.0;
  // A, to_X and the tensions' map of the build that filled the structure, but for the drive's
  // columns (build_pwl_mode: the same at every frequency).
  PwlMatrix A_frame, to_X_frame, lambda_frame;
  bool modal = false;  // V, V_inverse and lambda hold a well-conditioned eigendecomposition of A_zz
  PwlComplexMatrix V, V_inverse;
  PwlComplexVector lambda;
  PwlModalWeights weight;  // per modal coordinate (PwlModeSystem::weight)
  PwlComplexMatrix phi;    // PwlModeSystem::phi and force_V, which hold no drive column
  PwlComplexRow force_V;
};

struct PwlModeSystem {
  PwlModeCode code;
  int nz = 0, nh = 0, dim = 0;  // dim = nz + nh + 3
  int one() const { return nz + nh; }
  int sine() const { return nz + nh + 1; }
  int cosine() const { return nz + nh + 2; }

  PwlMatrix A;                             // dim x dim
  PwlMatrix to_X;                          // 2N x dim: X = (x, x') = to_X w
  PwlMatrix from_X;                        // dim x 2N: w = from_X X + drive terms (rows one, s, c: 0)
  PwlVector held_drive;                    // nh: h = R x + rho u, the rho of each rigid edge
  PwlRow force;                            // terminal force [N]
  PwlRow force_rate, force_curvature;      // force A and force A^2: dF/dt [N/s] and d2F/dt2 [N/s^2]
  PwlMatrix guards;                        // rows >= 0 while the mode holds
  PwlMatrix guard_rates;                   // guards A: their time derivatives
  std::vector<PwlTransition> transitions;  // one per guard row

  // The augmented state of node positions and velocities X where the drive's entries are
  // s = u0 sin(w t) and c = u0 cos(w t) [mm] (as a state of any mode at that time holds them).
  PwlVector state_at(const PwlVector& X, double s, double c) const;

  // The exact flow of the mode (pwl_flow.cpp): e^{A tau}, its action on a state, and
  // int_0^h F(w(tau)) e^{i omega tau} dtau. Where the state block A_zz is diagonalisable with
  // well-conditioned eigenvectors (reciprocal condition above 1e-8), in its modal coordinates
  // q = V^-1 z each q_j obeys q_j' = lambda_j q_j + phi_j + G+_j E e^{i w tau} + G-_j conj(E) e^{-i w tau}
  // (the constant forcing of h and 1, and the drive, E = c(0) + i s(0)), solved in closed form:
  //   q_j(tau) = e^{lambda tau} q_j(0) + sum_mu beta_mu e^{lambda tau} (e^{(mu - lambda) tau} - 1)/(mu - lambda),
  // mu in {0, i w, -i w}, which stays exact where mu = lambda (a slipping dashpot's drift at
  // lambda = 0, an undamped mass driven at resonance). Otherwise (a defective A_zz) the
  // exponential by Pade approximation with scaling and squaring.
  PwlMatrix propagator(double tau) const;
  // S <- e^{A tau} S for sensitivities S (dim x any) whose rows one, s and c are zero (dw/dX0:
  // the drive does not depend on the start): in modal coordinates the z rows are
  // Re V (e^{lambda tau} V^-1 S_z + P(lambda, 0, tau) phi_h S_h) (phi_h: phi's held columns),
  // the held rows stay; neither the propagator's drive columns nor a dim x dim product. Where
  // A_zz is defective, by the exponential.
  void propagate(double tau, PwlMatrix& S) const;
  PwlVector advance(double tau, const PwlVector& w) const;
  // w(tau + delta) from w = w(tau) by the Taylor series of e^{A delta}, where it reaches
  // rounding in a few terms (|delta| ||A^2||^(1/2) <= 0.05): the tail after term K is at most
  // (x1 + x2) x2^K / ((K + 1)! (1 - x2)) of ||w|| (infinity norms, x1 = |delta| ||A||, x2 =
  // |delta| ||A^2||^(1/2)), and K is the first that brings it below 1e-17. False (OUT
  // untouched) where delta is too long for that. A Newton iteration's short steps from its
  // last iterate so cost a few products instead of a flow's exponentials.
  bool nudge(double delta, const PwlVector& w, PwlVector& out) const;
  std::complex<double> phased_force_integral(double h, const PwlVector& w0) const;
  // Sets the modal data below (called by build_pwl_mode), the eigendecomposition taken from
  // STRUCTURE where it is filled, and stored there otherwise.
  void decompose(PwlModeStructure& structure);

  double reach = 0.0, reach_squared = 0.0;  // ||A|| and ||A^2||^(1/2) (infinity norms) [1/s]
  bool modal = false;
  double drive_omega = 0.0;                        // w [rad/s]
  PwlComplexMatrix V, V_inverse;                   // nz x nz
  PwlComplexVector lambda;                         // nz
  PwlModalWeights weight{};                        // nz: 2, 0 for a conjugate pair, 1 for a real eigenvalue
  PwlComplexMatrix phi;                            // nz x (nh + 1): V^-1 [A_zh, a_1]
  PwlComplexVector g_plus, g_minus;                // (1/2) V^-1 (a_c -+ i a_s) and its conjugate counterpart
  PwlComplexRow force_V;                           // force_z V
  PwlComplexVector gap_zero, gap_plus, gap_minus;  // 1/(mu - lambda_j) for mu = 0, i w, -i w (0 where mu = lambda_j)
};

// Builds the mode `code` of `branch` for angular frequency omega [rad/s] (every amplitude: the
// drive's entries of w carry it). False when the mode is indeterminate (a node or direction that nothing but
// slipping sliders and open gaps holds): such a mode cannot be physical, and the caller
// treats reaching it as a failure of the event-driven path. STRUCTURE, when given, is used if
// filled (it must come from the same branch and code) and filled otherwise.
bool build_pwl_mode(const PwlBranch& branch, const PwlModeCode& code, double omega, PwlModeSystem& out, PwlModeStructure* structure = nullptr);

}  // namespace rheo::runtime
