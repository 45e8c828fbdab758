#include "runtime/closed_form/pwl_mode.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

namespace rheo::runtime {
namespace {

// Every matrix of a build has the event path's fixed capacity (a mode of N internal nodes has
// dim = 2 N + r + 3 <= kPwlMaxDim): a build touches no heap.
using MatrixXd = PwlMatrix;
using RowVectorXd = PwlRow;
using VectorXd = PwlVector;

// Incidence of an edge over the internal nodes (d) and the terminal (d_T): e = d.x + d_T u.
struct Incidence {
  VectorXd d;
  double terminal = 0.0;
};

Incidence incidence(const PwlEdge& e, int nodes) {
  Incidence in{VectorXd::Zero(nodes), 0.0};
  if (e.a >= 0) in.d[e.a] += 1.0;
  if (e.b >= 0) in.d[e.b] -= 1.0;
  if (e.a == kPwlTerminal) in.terminal += 1.0;
  if (e.b == kPwlTerminal) in.terminal -= 1.0;
  return in;
}

// Orthonormal eigenvectors of a symmetric positive semi-definite matrix split at a relative
// threshold: columns with eigenvalue above it (`range`) and the others (`null`).
void split_by_eigenvalue(const MatrixXd& S, double reference, MatrixXd& range, MatrixXd& null) {
  const int n = static_cast<int>(S.rows());
  if (n == 0) {
    range.resize(0, 0), null.resize(0, 0);
    return;
  }
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(S);
  const double threshold = 1e-11 * std::max(reference, eig.eigenvalues().cwiseAbs().maxCoeff());
  std::vector<int> big, small;
  for (int i = 0; i < n; ++i) (eig.eigenvalues()[i] > threshold ? big : small).push_back(i);
  range.resize(n, static_cast<Eigen::Index>(big.size()));
  null.resize(n, static_cast<Eigen::Index>(small.size()));
  for (std::size_t i = 0; i < big.size(); ++i) range.col(static_cast<Eigen::Index>(i)) = eig.eigenvectors().col(big[i]);
  for (std::size_t i = 0; i < small.size(); ++i) null.col(static_cast<Eigen::Index>(i)) = eig.eigenvectors().col(small[i]);
}

}  // namespace

PwlVector PwlModeSystem::state_at(const PwlVector& X, double s, double c) const {
  PwlVector w;
  multiply(from_X, X, w);
  w.segment(nz, nh) += held_drive * s;
  w[one()] = 1.0;
  w[sine()] = s;
  w[cosine()] = c;
  return w;
}

bool build_pwl_mode(const PwlBranch& branch, const PwlModeCode& code, double omega, PwlModeSystem& out, PwlModeStructure* structure) {
  // A structure of its own only where none is given: its complex storage is cleared on construction (18 kB).
  std::unique_ptr<PwlModeStructure> local;
  if (structure == nullptr) local = std::make_unique<PwlModeStructure>();
  PwlModeStructure& st = structure != nullptr ? *structure : *local;
  if (st.filled && !st.determinate) return false;
  const bool first = !st.filled;  // this build fills the structure (and the frame below)
  const int n = branch.internal_nodes;
  if (!st.filled) {
    st.K = MatrixXd::Zero(n, n), st.C = st.K, st.M = st.K;
    st.kT = VectorXd::Zero(n), st.cT = st.kT, st.mT = st.kT, st.f_slip = st.kT;
    st.r = 0, st.guard_count = 0, st.largest_k = 0.0;
    st.incidence.clear(), st.terminal.clear();
    for (const PwlEdge& e : branch.edges) {
      Incidence in = incidence(e, n);
      st.incidence.push_back(in.d), st.terminal.push_back(in.terminal);
    }
    for (std::size_t s = 0; s < branch.switches.size(); ++s) {
      const auto edge = static_cast<std::size_t>(branch.switches[s]);
      const PwlEdge& e = branch.edges[edge];
      st.guard_count += (code[s] == 0) ? 2 : 1;  // two rows for a stuck slider or an open gap, one for a slipping slider or a closed gap
      if (code[s] == 0 && e.kind == PwlEdgeKind::gap) continue;  // open: no force
      if (code[s] != 0 && e.kind == PwlEdgeKind::slider) {
        st.f_slip += st.incidence[edge] * e.slip_force(code[s]);
        continue;
      }
      if (st.r == kPwlMaxDim) return false;  // not reached: PwlBranch::build keeps dim within kPwlMaxDim
      st.rigid[static_cast<std::size_t>(st.r++)] = branch.switches[s];
    }
    for (std::size_t i = 0; i < branch.edges.size(); ++i) {
      const PwlEdge& e = branch.edges[i];
      const VectorXd& d = st.incidence[i];
      const double terminal = st.terminal[i];
      switch (e.kind) {
        case PwlEdgeKind::spring:
          st.K += e.value * d * d.transpose(), st.kT += e.value * terminal * d;
          st.largest_k = std::max(st.largest_k, e.value);
          break;
        case PwlEdgeKind::dashpot: st.C += e.value * d * d.transpose(), st.cT += e.value * terminal * d; break;
        case PwlEdgeKind::inerter: st.M += e.value * d * d.transpose(), st.mT += e.value * terminal * d; break;
        default: break;
      }
    }
    // Rigid constraints R x + rho u = h and the split x = P (h - rho u) + N y.
    st.R.resize(st.r, n), st.rho.resize(st.r);
    for (int i = 0; i < st.r; ++i) {
      const auto edge = static_cast<std::size_t>(st.rigid[static_cast<std::size_t>(i)]);
      st.R.row(i) = st.incidence[edge].transpose();
      st.rho[i] = st.terminal[edge];
    }
    const MatrixXd& R = st.R;
    st.P = MatrixXd::Zero(n, st.r), st.N = MatrixXd::Identity(n, n);
    if (st.r > 0) {
      st.P = R.transpose() * (R * R.transpose()).inverse();
      MatrixXd range, null;
      split_by_eigenvalue(R.transpose() * R, 1.0, range, null);
      st.N = null;
    }
    const MatrixXd &K = st.K, &C = st.C, &M = st.M, &P = st.P, &N = st.N;
    st.Kq = N.transpose() * K * N, st.Cq = N.transpose() * C * N;
    const MatrixXd Mq = N.transpose() * M * N;
    // Directions: massive (m), massless damped (d), massless undamped (a).
    MatrixXd V0, Vd0;
    split_by_eigenvalue(Mq, 0.0, st.Vm, V0);
    split_by_eigenvalue(V0.transpose() * st.Cq * V0, 0.0, Vd0, st.Va);
    st.Vd = V0 * Vd0, st.Va = V0 * st.Va;
    st.Fy_held = -N.transpose() * K * P;
    st.Fy_one = -N.transpose() * st.f_slip;
    st.P_rho = P * st.rho;
    st.drive_k = K * P * st.rho - st.kT;
    st.drive_m = M * P * st.rho - st.mT;
    st.drive_c = C * P * st.rho - st.cT;
  }
  const MatrixXd &K = st.K, &C = st.C, &M = st.M, &R = st.R, &P = st.P, &N = st.N;
  const VectorXd &kT = st.kT, &cT = st.cT, &mT = st.mT, &f_slip = st.f_slip, &rho = st.rho;
  const int r = st.r, nq = static_cast<int>(N.cols());
  const MatrixXd &Kq = st.Kq, &Vm = st.Vm, &Vd = st.Vd, &Va = st.Va;
  const int nm = static_cast<int>(Vm.cols()), nd = static_cast<int>(Vd.cols()), na = static_cast<int>(Va.cols());

  // Layout of w.
  out.code = code;
  out.nz = nd + 2 * nm;
  out.nh = r;
  out.dim = out.nz + r + 3;
  const int dim = out.dim, iz_m = nd, iz_v = nd + nm, ih = out.nz, i1 = out.one(), is = out.sine(), ic = out.cosine();

  // Generalised force on y as a functional of w: N^T [ (K P rho - k_T) u + (C P rho - c_T) u'
  // + (M P rho - m_T) u'' - f_slip - K P h ], with u = u0 s, u' = w u0 c, u'' = -w^2 u0 s (u0 s
  // and u0 c the drive's entries of w).
  // Its drive's columns are formed below (Fd); in the frame they are zero.
  MatrixXd Fy;
  if (first) {
    Fy = MatrixXd::Zero(nq, dim);
    Fy.middleCols(ih, r) = st.Fy_held;
    Fy.col(i1) = st.Fy_one;
  }

  if (!st.filled) {
    // Selections of eta_d, eta_m, v_m from w, and the products of the condensation and the
    // dynamics below that hold no drive column.
    st.Sd = MatrixXd::Zero(nd, dim), st.Sm = MatrixXd::Zero(nm, dim), st.Sv = MatrixXd::Zero(nm, dim);
    for (int i = 0; i < nd; ++i) st.Sd(i, i) = 1.0;
    for (int i = 0; i < nm; ++i) st.Sm(i, iz_m + i) = 1.0, st.Sv(i, iz_v + i) = 1.0;
    st.Vd_Sd = Vd * st.Sd, st.Vm_Sm = Vm * st.Sm, st.Vm_Sv = Vm * st.Sv;
    if (na > 0) {
      const MatrixXd Kaa = Va.transpose() * Kq * Va;
      Eigen::SelfAdjointEigenSolver<MatrixXd> eig(Kaa);
      if (!(eig.eigenvalues().minCoeff() > 1e-11 * std::max(st.largest_k, 1e-300))) {
        st.filled = true, st.determinate = false;
        return false;
      }
      st.Kaa_inverse = eig.eigenvectors() * eig.eigenvalues().cwiseInverse().asDiagonal() * eig.eigenvectors().transpose();
      st.condensed = Va.transpose() * Kq * (st.Vd_Sd + st.Vm_Sm);
    }
    const MatrixXd& Cq = st.Cq;
    if (nd > 0) st.Cdd_inverse = (Vd.transpose() * Cq * Vd).inverse(), st.damped_coupling = Vd.transpose() * Cq * Vm * st.Sv;
    if (nm > 0) st.Mmm_inverse = (Vm.transpose() * (N.transpose() * M * N) * Vm).inverse(), st.Vm_Cq = Vm.transpose() * Cq;
    st.from_X = MatrixXd::Zero(dim, 2 * n);
    const MatrixXd toq = N.transpose();
    st.from_X.block(0, 0, nd, n) = Vd.transpose() * toq;
    st.from_X.block(iz_m, 0, nm, n) = Vm.transpose() * toq;
    st.from_X.block(iz_v, n, nm, n) = Vm.transpose() * toq;
    st.from_X.block(ih, 0, r, n) = R;
    st.tensions = MatrixXd::Zero(r, n);
    if (r > 0) st.tensions = -(R * R.transpose()).inverse() * R;
  }

  // A's rows s and c hold only the drive's rotation, and its other columns than s and c no entry
  // outside the z rows, so every product below is the same in those columns at every frequency:
  // the build that fills the structure forms A, X's maps and the tensions whole and keeps them
  // (the frame), and every build then forms the drive's columns alone, by the same products
  // restricted to them, so that a mode is the same to the last bit whichever frequency built it
  // first.
  MatrixXd lambda;
  if (first) {
    // Static condensation of the undamped massless directions: K_aa eta_a = Va^T Fy w - K_ad eta_d - K_am eta_m.
    MatrixXd Ea = MatrixXd::Zero(na, dim);
    if (na > 0) Ea = st.Kaa_inverse * (Va.transpose() * Fy - st.condensed);
    // y = Va eta_a + Vd eta_d + Vm eta_m as a functional of w.
    const MatrixXd Y = Va * Ea + st.Vd_Sd + st.Vm_Sm;
    const MatrixXd elastic = Fy - Kq * Y;  // generalised force less the stiffness term
    out.A = MatrixXd::Zero(dim, dim);
    MatrixXd Ad = MatrixXd::Zero(nd, dim);
    if (nd > 0) Ad = st.Cdd_inverse * (Vd.transpose() * elastic - st.damped_coupling);
    out.A.middleRows(0, nd) = Ad;
    out.A.middleRows(iz_m, nm) = st.Sv;
    if (nm > 0) out.A.middleRows(iz_v, nm) = st.Mmm_inverse * (Vm.transpose() * elastic - st.Vm_Cq * (Vd * Ad + st.Vm_Sv));
    // Positions and velocities.
    MatrixXd Lx = N * Y;
    Lx.middleCols(ih, r) += P;
    const MatrixXd Lv = Lx * out.A, La = Lv * out.A;
    out.to_X.resize(2 * n, dim);
    out.to_X << Lx, Lv;
    // Tensions of the rigid edges from the full equilibrium.
    lambda = MatrixXd::Zero(r, dim);
    if (r > 0) {
      MatrixXd residual = M * La + C * Lv + K * Lx;
      residual.col(i1) += f_slip;
      lambda = st.tensions * residual;
    }
    st.A_frame = out.A, st.to_X_frame = out.to_X, st.lambda_frame = lambda;
  } else {
    out.A = st.A_frame, out.to_X = st.to_X_frame, lambda = st.lambda_frame;
  }
  // The drive's columns: the generalised force's, then as above.
  MatrixXd Fd(nq, 2);
  Fd.col(0) = N.transpose() * (st.drive_k - omega * omega * st.drive_m);
  Fd.col(1) = omega * N.transpose() * st.drive_c;
  MatrixXd Ed = MatrixXd::Zero(na, 2);
  if (na > 0) Ed = st.Kaa_inverse * (Va.transpose() * Fd - st.condensed.middleCols(is, 2));
  const MatrixXd Yd = Va * Ed + st.Vd_Sd.middleCols(is, 2) + st.Vm_Sm.middleCols(is, 2);
  const MatrixXd elastic_d = Fd - Kq * Yd;
  MatrixXd Ad = MatrixXd::Zero(nd, 2);
  if (nd > 0) Ad = st.Cdd_inverse * (Vd.transpose() * elastic_d - st.damped_coupling.middleCols(is, 2));
  out.A.block(0, is, nd, 2) = Ad;
  if (nm > 0) out.A.block(iz_v, is, nm, 2) = st.Mmm_inverse * (Vm.transpose() * elastic_d - st.Vm_Cq * (Vd * Ad + st.Vm_Sv.middleCols(is, 2)));
  out.drive_omega = omega;
  out.A(is, ic) = omega;
  out.A(ic, is) = -omega;
  MatrixXd Lx_d = N * Yd;
  Lx_d.col(0) -= st.P_rho;
  out.to_X.block(0, is, n, 2) = Lx_d;
  const MatrixXd Lx = out.to_X.topRows(n);
  const MatrixXd Lv_d = Lx * out.A.middleCols(is, 2);
  out.to_X.block(n, is, n, 2) = Lv_d;
  if (r > 0) {
    const MatrixXd La_d = out.to_X.bottomRows(n) * out.A.middleCols(is, 2);
    MatrixXd residual = M * La_d + C * Lv_d + K * Lx_d;
    residual.col(0) += kT - omega * omega * mT;
    residual.col(1) += omega * cT;
    lambda.middleCols(is, 2) = st.tensions * residual;
  }
  out.from_X = st.from_X;
  out.held_drive = rho;

  // Edge forces, the terminal force and the guards.
  out.force = RowVectorXd::Zero(dim);
  out.guards.resize(st.guard_count, dim);
  out.transitions.clear();
  auto guard = [&](const RowVectorXd& row, int which, std::int8_t to, double scale, double per_amplitude) {
    out.guards.row(static_cast<Eigen::Index>(out.transitions.size())) = row;
    out.transitions.push_back({which, to, scale, per_amplitude});
  };
  int rigid_index = 0;
  std::size_t switch_index = 0;
  for (std::size_t i = 0; i < branch.edges.size(); ++i) {
    const PwlEdge& e = branch.edges[i];
    const double terminal = st.terminal[i];
    RowVectorXd elongation = st.incidence[i].transpose() * Lx;
    elongation[is] += terminal;
    RowVectorXd force = RowVectorXd::Zero(dim);
    const bool is_switch = switch_index < branch.switches.size() && branch.switches[switch_index] == static_cast<int>(i);
    const int which = static_cast<int>(switch_index);
    const std::int8_t state = is_switch ? code[switch_index++] : 0;
    switch (e.kind) {
      case PwlEdgeKind::spring: force = e.value * elongation; break;
      case PwlEdgeKind::dashpot: force = e.value * elongation * out.A; break;
      case PwlEdgeKind::inerter: force = e.value * elongation * out.A * out.A; break;
      case PwlEdgeKind::slider:
        if (state == 0) {
          force = lambda.row(rigid_index++);
          RowVectorXd upper = -force, lower = force;  // fy+ - F >= 0, F + fy- >= 0
          // Sized max(fy, k u0) as a closed gap's force is: the force follows from positions
          // through springs up to the stiffest, so its rounding is ~eps k u0. Sized by fy alone,
          // a slider with fy far below k u0 (1e-4 N behind 7840 N/mm, as a diagnosis's global
          // look samples) read rounding as leaving at every check and no mode held it.
          upper[i1] += e.value, lower[i1] += e.cap_neg;
          guard(upper, which, 1, e.value, st.largest_k);
          guard(lower, which, -1, e.cap_neg, st.largest_k);
        } else {
          force[i1] = e.slip_force(state);
          guard(state * elongation * out.A, which, 0, 0.0, omega);  // u0 w
        }
        break;
      case PwlEdgeKind::gap:
        if (state == 0) {
          RowVectorXd upper = -elongation, lower = elongation;  // c + w/2 - e >= 0, e - (c - w/2) >= 0
          upper[i1] += e.center + e.value, lower[i1] += e.value - e.center;
          guard(upper, which, 1, e.value, 1e-9);
          guard(lower, which, -1, e.value, 1e-9);
        } else {
          force = lambda.row(rigid_index++);
          guard(state * force, which, 0, 1e-300, st.largest_k);  // k u0
        }
        break;
    }
    out.force += terminal * force;
  }
  out.guard_rates = out.guards * out.A;
  out.force_rate = out.force * out.A;
  out.force_curvature = out.force_rate * out.A;
  out.reach = out.A.cwiseAbs().rowwise().sum().maxCoeff();
  out.reach_squared = std::sqrt((out.A * out.A).cwiseAbs().rowwise().sum().maxCoeff());
  out.decompose(st);
  st.filled = true;
  return true;
}

}  // namespace rheo::runtime
