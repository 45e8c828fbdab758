#include "runtime/fit/parameter_bounds.hpp"

#include <cmath>

namespace rheo::runtime {

bool logarithmic_search(const lang::Parameter& p) { return p.lower > 0.0; }

double search_coordinate(const lang::Parameter& p, double value) { return logarithmic_search(p) ? std::log(value) : value; }

BoundSide bound_reached(const lang::Parameter& p, double value) {
  if (!p.free || !(p.upper > p.lower)) return BoundSide::none;
  const double z = search_coordinate(p, value), lower = search_coordinate(p, p.lower), upper = search_coordinate(p, p.upper);
  const double margin = kAtBoundFraction * (upper - lower);
  if (z - lower <= margin) return BoundSide::lower;
  if (upper - z <= margin) return BoundSide::upper;
  return BoundSide::none;
}

}  // namespace rheo::runtime
