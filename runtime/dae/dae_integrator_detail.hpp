// Internals shared by the translation units of DaeIntegrator (dae_integrator.cpp: set-up,
// residuals and stepping; dae_events.cpp: mode switches and restarts). Not for other users.
#pragma once

#include "runtime/dae/dae_integrator.hpp"
#include "runtime/dae/sundials_owners.hpp"

#include <Eigen/Dense>

#include <cstddef>
#include <vector>

namespace rheo::runtime {

// A stuck slider slips when |F| exceeds fy (1 + kSlack) and stays stuck after a velocity reversal
// while |F| <= fy (1 + kSlack/2); the margin keeps the switch from chattering on roundoff at the
// instant of reversal, where |F| = fy. A gap closes when |e - c| exceeds w/2 (1 + kGapSlack).
// fy is fy_pos on the tension side (F > 0) and fy_neg on the compression side.
inline constexpr double kSlack = 1e-6;
inline constexpr double kGapSlack = 1e-9;
// IDA's default Newton convergence coefficient (IDASetNonlinConvCoef).
inline constexpr double kIdaNewtonCoefficient = 0.33;

// The force of slider EDGE slipping in direction MODE (+1 or -1): fy_pos or -fy_neg.
inline double slip_force(const Edge& slider, int mode) { return mode > 0 ? slider.p[0] : -slider.p[1]; }
// The elongation at which gap EDGE closes on side MODE (+1 or -1): c + mode w/2.
inline double gap_stop(const Edge& gap, int mode) { return gap.p[1] + mode * gap.p[0]; }

struct DaeIntegrator::Solver {
  sundials::Context context;
  sundials::Vector y, yp, id, tolerance;
  sundials::Matrix jacobian;
  sundials::LinearSolver linear_solver;
  sundials::IdaMemory ida;
  std::vector<double> euler_matrix;               // n x n, column-major: initial_rates_by_euler_step
  Eigen::PartialPivLU<Eigen::MatrixXd> euler_lu;  // sized once
};

// Element I of V, for the int indices the graph and the layout use.
template <class T>
T& at(std::vector<T>& v, int i) {
  return v[static_cast<std::size_t>(i)];
}
template <class T>
const T& at(const std::vector<T>& v, int i) {
  return v[static_cast<std::size_t>(i)];
}

}  // namespace rheo::runtime
