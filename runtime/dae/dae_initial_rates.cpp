// DaeIntegrator's consistent rates where IDACalcIC cannot find them: networks with a bouc_wen
// between internal nodes (the contract is in dae_integrator.hpp, initial_rates_by_euler_step).
#include "runtime/dae/dae_integrator.hpp"

#include "runtime/dae/dae_integrator_detail.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace rheo::runtime {

// A Bouc-Wen law z' = (k/fy) e' (1 - |z|^n (1 + sgn(z e'))/2) reads its elongation's rate, and
// inside a block that is a difference of node positions' rates x': the positions, algebraic in
// IDA's sense (id 0), have rates that the DAE fixes only through the time derivative of the node
// balances (a bouc_wen in series with a spring: k (u' - x') = fy z'). IDACalcIC
// (IDA_YA_YDP_INIT) holds x' fixed while it solves for x and the differential rates, so it
// cannot make z' consistent, and where a node's balance holds Bouc-Wen forces alone (two
// bouc_wen in series) no algebraic unknown appears in that balance and its Newton matrix is
// singular (IDA_LINESEARCH_FAIL at t = 0).
//
// Instead, with y consistent at t (a start at rest or relaxed, or a sample of the drive: such
// networks have no sliders or gaps, DaeGraph::build), the rates y' of every unknown are those of
// one backward-Euler step of length h from (t, y): F(t + h, y + h v, v) = 0, solved for v by
// Newton with the matrix dF/dv = h (dF/dy + (1/h) dF/dy') (jacobian() at c_j = 1/h). Its
// algebraic rows at t + h are the node balances' time derivatives to O(h), its differential
// rows the laws: v is the consistent y' to O(h y''), h = 1e-6 of the drive's time scale.
void DaeIntegrator::initial_rates_by_euler_step(double t, double horizon) { euler_rates(t, 1e-3 * horizon); }

// Newton with the matrix recomputed at every iterate (IDA's corrector keeps the one of its
// predictor), from v = yp_; y_ is left as it is.
void DaeIntegrator::euler_rates(double t, double h) {
  if (!try_euler_rates(t, h))
    throw NumericalError(fmt::format("model '{}': no consistent rates at t = {:g} s (Newton on a backward-Euler step of {:g} s did not converge)",
                                     graph_.model, t, h));
}

bool DaeIntegrator::try_euler_rates(double t, double h) {
  const int n = layout_.size();
  const double per_second = options_.velocity_scale / options_.length_scale;
  Eigen::Map<Eigen::MatrixXd> matrix(solver_->euler_matrix.data(), n, n);
  std::vector<double>& y1 = y_probe_initial_;
  std::vector<double>& g = r_initial_;
  std::vector<double>& v = yp_;
  for (int iteration = 0; iteration < 30; ++iteration) {
    for (int i = 0; i < n; ++i) at(y1, i) = at(y_, i) + h * at(v, i);
    residual(t + h, y1.data(), v.data(), g.data());
    jacobian(t + h, 1.0 / h, y1.data(), v.data(), g.data(), matrix.data());
    solver_->euler_lu.compute(matrix);
    Eigen::Map<Eigen::VectorXd> step(g.data(), n);
    step = solver_->euler_lu.solve(step);  // M^-1 G; the Newton step of v is that over h
    double change = 0.0;
    for (int i = 0; i < n; ++i) {
      const double dv = at(g, i) / h;
      at(v, i) -= dv;
      change = std::max(change, std::abs(dv) / (std::abs(at(v, i)) + at(scale_, i) * per_second));
    }
    // v seeds IDA's predictor (or moves y by h v): 1e-6 of the rate's scale is ample, and the
    // roundoff of G / h (forces to 1e-16 over steps of 1e-6 of the time scale) sets a floor of
    // about 1e-8 where the rates nearly vanish.
    if (change <= 1e-6) return true;
  }
  return false;
}

// One backward-Euler step of length h from (t, y_): see solve_to, where IDA's corrector fails
// at the start of an interval.
void DaeIntegrator::euler_step(double t, double h) {
  euler_rates(t, h);
  for (int i = 0; i < layout_.size(); ++i) at(y_, i) += h * at(yp_, i);
  time_ = t + h;
}

}  // namespace rheo::runtime
