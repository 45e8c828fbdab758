#include "runtime/dae/dae_modes.hpp"

#include "runtime/core/errors.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

namespace rheo::runtime {
namespace {

// Row of an edge's elongation: e = D x + d u.
void edge_row(const Edge& edge, int nodes, Eigen::RowVectorXd& row, double& drive) {
  row = Eigen::RowVectorXd::Zero(nodes);
  drive = 0.0;
  if (edge.a >= 0) row[edge.a] += 1.0;
  if (edge.b >= 0) row[edge.b] -= 1.0;
  if (edge.a == kTerminal) drive += 1.0;
  if (edge.b == kTerminal) drive -= 1.0;
}

}  // namespace

bool is_rigid(const Edge& edge, std::int8_t mode) { return edge.kind == EdgeKind::slider ? mode == 0 : mode != 0; }

ModeKinematics ModeKinematics::make(const DaeGraph& graph, const SwitchModes& modes) {
  const int m = graph.internal_nodes;
  Eigen::RowVectorXd row;
  double drive = 0.0;

  // Rigid constraints R x + r u = const, their null space N and the particular rate p u'.
  std::vector<int> rigid;
  for (std::size_t l = 0; l < graph.switch_edges.size(); ++l)
    if (is_rigid(graph.edges[static_cast<std::size_t>(graph.switch_edges[l])], modes[l])) rigid.push_back(graph.switch_edges[l]);
  Eigen::MatrixXd R(static_cast<Eigen::Index>(rigid.size()), m);
  Eigen::VectorXd r(static_cast<Eigen::Index>(rigid.size()));
  for (std::size_t i = 0; i < rigid.size(); ++i) {
    edge_row(graph.edges[static_cast<std::size_t>(rigid[i])], m, row, drive);
    R.row(static_cast<Eigen::Index>(i)) = row;
    r[static_cast<Eigen::Index>(i)] = drive;
  }
  Eigen::MatrixXd N = Eigen::MatrixXd::Identity(m, m);
  Eigen::VectorXd p = Eigen::VectorXd::Zero(m);
  if (!rigid.empty() && m > 0) {
    Eigen::FullPivLU<Eigen::MatrixXd> lu(R);
    N = lu.dimensionOfKernel() == 0 ? Eigen::MatrixXd(m, 0) : Eigen::MatrixXd(lu.kernel());
    p = -R.completeOrthogonalDecomposition().solve(r);
  }

  // Greedy basis of the reduced rate rows D_r N: inerters first (Gram-Schmidt on the rows).
  const auto n_rate = graph.rate_edges.size();
  std::vector<Eigen::RowVectorXd> reduced(n_rate);
  std::vector<double> particular(n_rate);  // D_r p + d_r
  for (std::size_t i = 0; i < n_rate; ++i) {
    edge_row(graph.edges[static_cast<std::size_t>(graph.rate_edges[i])], m, row, drive);
    reduced[i] = row * N;
    particular[i] = row.dot(p) + drive;
  }
  std::vector<std::size_t> order;
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t i = 0; i < n_rate; ++i) {
      const bool inerter = graph.edges[static_cast<std::size_t>(graph.rate_edges[i])].kind == EdgeKind::inerter;
      if (inerter == (pass == 0)) order.push_back(i);
    }
  ModeKinematics k;
  std::vector<Eigen::RowVectorXd> basis;
  int next_velocity_slot = 0;
  for (std::size_t i : order) {
    Eigen::RowVectorXd rest = reduced[i];
    const double size = rest.norm();
    if (size <= 1e-12) continue;
    for (const auto& q : basis) rest -= rest.dot(q) * q;
    if (rest.norm() <= 1e-9 * size) continue;
    basis.push_back(rest / rest.norm());
    k.coordinate_rate.push_back(static_cast<int>(i));
    const bool inerter = graph.edges[static_cast<std::size_t>(graph.rate_edges[i])].kind == EdgeKind::inerter;
    k.velocity_slot.push_back(inerter ? next_velocity_slot++ : -1);
  }
  k.coordinates = static_cast<int>(k.coordinate_rate.size());

  // alpha_r solves S^T alpha_r = (D_r N)^T, S the chosen rows; beta_r = particular_r - sum alpha particular_j.
  const int q = k.coordinates;
  k.alpha.assign(n_rate * static_cast<std::size_t>(q), 0.0);
  k.beta.assign(n_rate, 0.0);
  Eigen::MatrixXd S(q, N.cols());
  for (int j = 0; j < q; ++j) S.row(j) = reduced[static_cast<std::size_t>(k.coordinate_rate[static_cast<std::size_t>(j)])];
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> decomposition;
  if (q > 0) decomposition.compute(S.transpose());
  for (std::size_t i = 0; i < n_rate; ++i) {
    const Edge& edge = graph.edges[static_cast<std::size_t>(graph.rate_edges[i])];
    Eigen::VectorXd a = q > 0 ? Eigen::VectorXd(decomposition.solve(reduced[i].transpose())) : Eigen::VectorXd(0);
    double beta = particular[i];
    for (int j = 0; j < q; ++j) {
      double& alpha = k.alpha[i * static_cast<std::size_t>(q) + static_cast<std::size_t>(j)];
      alpha = std::abs(a[j]) < 1e-12 ? 0.0 : a[j];
      beta -= alpha * particular[static_cast<std::size_t>(k.coordinate_rate[static_cast<std::size_t>(j)])];
      if (edge.kind == EdgeKind::inerter && alpha != 0.0 && k.velocity_slot[static_cast<std::size_t>(j)] < 0)
        throw NumericalError(
            fmt::format("{}inerter '{}' of model '{}' moves with a dashpot coordinate in this state; "
                        "use solver = fixed",
                        error_at(edge.where), edge.path, graph.model));
    }
    k.beta[i] = std::abs(beta) < 1e-12 ? 0.0 : beta;
    if (edge.kind == EdgeKind::inerter && reduced[i].norm() <= 1e-12)
      throw NumericalError(
          fmt::format("{}inerter '{}' of model '{}' is held rigidly to the drive by a stuck slider or closed gap, so its force would "
                      "need the drive's acceleration; put a spring in series with it, or use solver = fixed",
                      error_at(edge.where), edge.path, graph.model));
  }
  return k;
}

}  // namespace rheo::runtime
