// The Jacobian dr/dz of a fit's residual vector (fit_scoring.hpp) in the search coordinates z
// (fit_coordinates.hpp), by sensitivities rather than by differencing the simulation, for fits
// whose every prediction is a closed-form harmonic point of a network with all its elements in
// the root parallel block (closed_form_sensitivity.hpp).
//
// Chain rule, per harmonic point i and free parameter j:
//   dr_i/dz_j = sum_k (dr_i/dm) (dm/dC_k) (dC_k/dz_j),
// with m = (F^, K'_1, K''_1) the point's summary, C the root coefficients and
//   dm/dC_k   analytic (closed_form_sensitivity.hpp);
//   dC_k/dz_j central differences of Network::with_parameters at z_j -+ 1e-4 max(|z_j|, 1)
//             (no simulation: the coefficients are the parameters, or expressions of them, and
//             a springpot's modes; for those affine in p exact to rounding, ~1e-12 relative);
//   dr_i/dm   the derivative of the residual terms of fit_scoring.hpp:
//             phi:  sqrt(w_K) g s_m/(s_e K_exp) dK,   sqrt(w_d) g dsin(phase)/sin(phase_exp)
//                   (s = sign of the storage part, as stiffness_residual signs K; the damping
//                   row 0 where its term is left out);
//             least_squares: g (dK cos + K dcos) / K_exp,  g (dK sin + K dsin) / K_exp,
//             g the point's scale sqrt(w_f / (2 m_f)) (times sqrt(weight_i)).
// The residuals at z are returned with it, bitwise those fit_scoring.hpp makes.
#pragma once

#include "runtime/fit/fit_coordinates.hpp"
#include "runtime/fit/fit_scoring.hpp"

#include <Eigen/Core>

#include <vector>

namespace rheo::runtime {

// True when residual_jacobian serves the residuals of METHOD: the exact method, every data set a
// harmonic table without preload, every point by the closed form (uses_closed_form) and every
// element of NETWORK in its root parallel block.
bool residual_jacobian_applies(const Network& network, const std::vector<FitDataSet>& data, const ScoreSettings& score, FitMethod method);

struct ResidualsWithJacobian {
  std::vector<double> residuals;
  Eigen::MatrixXd jacobian;  // residuals x free parameters; empty where the coefficients could not be differenced
};

// Requires residual_jacobian_applies(coordinates.network(z), data, score, FitMethod::exact).
// NumericalError where a point cannot be evaluated (as the residuals would throw).
ResidualsWithJacobian residual_jacobian(const Coordinates& coordinates, const std::vector<double>& z, const std::vector<FitDataSet>& data,
                                        const ScoreSettings& score);

}  // namespace rheo::runtime
