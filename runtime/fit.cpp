#include "runtime/fit.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace rheo::runtime {

FitResult fit_harmonic(const Network& start, const HarmonicData& data, const FitSettings& settings) {
  const auto& parameters = start.model().parameters;
  std::vector<int> free;
  std::vector<bool> logarithmic;
  std::vector<double> z, lower, upper;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    const auto& p = parameters[i];
    if (!p.free) continue;
    const bool log_space = p.lower > 0.0;
    free.push_back(static_cast<int>(i));
    logarithmic.push_back(log_space);
    auto map = [&](double v) { return log_space ? std::log(v) : v; };
    z.push_back(map(start.parameter(static_cast<int>(i))));
    lower.push_back(map(p.lower));
    upper.push_back(map(p.upper));
  }
  if (free.empty())
    throw std::invalid_argument(fmt::format("model '{}' has no free parameter; give bounds to the ones to fit, e.g. `k = 300 N/mm in [10, 5000]`",
                                            start.model().name));
  auto values_of = [&](const std::vector<double>& x) {
    std::vector<double> values = start.parameters();
    for (std::size_t j = 0; j < free.size(); ++j)
      values[static_cast<std::size_t>(free[j])] = logarithmic[j] ? std::exp(x[j]) : x[j];
    return values;
  };
  auto residuals_at = [&](const Network& network) {
    return relative_residuals(data, simulate_at(network, data, settings.harmonic));
  };
  const Objective objective = [&](const std::vector<double>& x) {
    return phi(residuals_at(start.with_parameters(values_of(x))), settings.stiffness_weight, settings.damping_weight);
  };
  OptimizationResult optimum = minimize(objective, z, lower, upper, settings.optimizer);
  Network fitted = start.with_parameters(values_of(optimum.x));
  const RelativeResiduals r = residuals_at(fitted);
  return {fitted, free, phi(r, settings.stiffness_weight, settings.damping_weight), thesis_err(r), optimum};
}

}  // namespace rheo::runtime
