// Tick positions and labels of plot axes.
//
// Linear: steps of 1, 2 or 5 x 10^k, about `target` ticks over [lo, hi], labels without
// floating-point noise ("0.3", not "0.30000000000000004"). Logarithmic (lo > 0): decades
// 10^k; over fewer decades also 2 and 5 x 10^k (below 2.3 decades), 2, 3 and 5 x 10^k (below
// 1.3), every mantissa 1..9 (below 0.5); a range too narrow for two such ticks gets linear ones.
#pragma once

#include <string>
#include <vector>

namespace rheo::runtime::report {

struct Tick {
  double value = 0.0;
  std::string label;
};

std::vector<Tick> linear_ticks(double lo, double hi, int target = 6);
std::vector<Tick> log_ticks(double lo, double hi);

// The 1-2-5 step closest to span / target.
double nice_step(double span, int target);

}  // namespace rheo::runtime::report
