// Bound-constrained minimisation with NLopt 2.7.1 (C API).
//
// The nlopt_opt handle lives in an RAII owner; every return code is checked and reported with
// the name of the call; the objective is called through a noexcept trampoline that stores any
// exception, forces NLopt to stop, and rethrows it after nlopt_optimize returns. A non-finite
// objective value is replaced by a penalty, the worst finite value seen so far plus ten times
// its magnitude (+1e300 before any finite one), so that derivative-free methods back away from
// it without their local models being ruined; it is counted in the result.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace rheo::runtime {

enum class Algorithm { bobyqa, sbplx, neldermead, direct_l, crs2, isres, mlsl };

struct OptimizerSettings {
  Algorithm algorithm = Algorithm::bobyqa;
  int max_evaluations = 2000;
  double relative_x_tolerance = 1e-10;  // local methods only; global ones use max_evaluations
  double relative_f_tolerance = 1e-14;
  unsigned long seed = 1;  // for the stochastic global methods: a fixed seed, the same result
};

struct OptimizationResult {
  std::vector<double> x;
  double value = 0.0;
  int evaluations = 0;
  int non_finite = 0;  // evaluations that returned NaN or inf
  std::string status;  // NLopt's result code, e.g. "NLOPT_XTOL_REACHED"
};

using Objective = std::function<double(const std::vector<double>&)>;

OptimizationResult minimize(const Objective& objective, std::vector<double> start, const std::vector<double>& lower,
                            const std::vector<double>& upper, const OptimizerSettings& settings);

}  // namespace rheo::runtime
