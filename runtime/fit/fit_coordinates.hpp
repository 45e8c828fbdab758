// The search coordinates of a fit (fit.hpp): z = ln p for a free parameter whose bounds are
// positive, z = p otherwise, mapped to and from the model's full parameter vector.
#pragma once

#include "runtime/fit/parameter_bounds.hpp"
#include "runtime/network/network.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace rheo::runtime {

// Maps search coordinates z to the full parameter vector of the model.
class Coordinates {
 public:
  Coordinates(const Network& start, const std::vector<int>& free) : start_(start), free_(free) {
    const auto& parameters = start.model().parameters;
    for (int i : free) {
      const auto& p = parameters.at(static_cast<std::size_t>(i));
      if (!p.free)
        throw std::logic_error(fmt::format("parameter '{}' has no bounds; give it bounds to fit it, e.g. `{} in [lo, hi]`", p.path, p.path));
      const bool log_space = logarithmic_search(p);
      logarithmic.push_back(log_space);
      auto map = [&](double v) { return log_space ? std::log(v) : v; };
      z0.push_back(map(start.parameter(i)));
      lower.push_back(map(p.lower));
      upper.push_back(map(p.upper));
    }
  }
  std::vector<double> values(const std::vector<double>& z) const {
    std::vector<double> v = start_.parameters();
    for (std::size_t j = 0; j < free_.size(); ++j) v[static_cast<std::size_t>(free_[j])] = logarithmic[j] ? std::exp(z[j]) : z[j];
    return v;
  }
  Network network(const std::vector<double>& z) const { return start_.with_parameters(values(z)); }
  // The coordinates of the free parameters' values in `values` (every model parameter).
  std::vector<double> z_of(const std::vector<double>& values) const {
    std::vector<double> z(free_.size());
    for (std::size_t j = 0; j < free_.size(); ++j) {
      const double v = values[static_cast<std::size_t>(free_[j])];
      z[j] = logarithmic[j] ? std::log(v) : v;
    }
    return z;
  }
  const std::vector<int>& free() const { return free_; }
  const lang::CheckedModel& model() const { return start_.model(); }

  std::vector<double> z0, lower, upper;
  std::vector<bool> logarithmic;

 private:
  const Network& start_;
  const std::vector<int>& free_;
};

}  // namespace rheo::runtime
