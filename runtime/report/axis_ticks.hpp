// Tick positions and labels of plot axes.
//
// Linear: steps of 1, 2 or 5 x 10^k, about `target` ticks over [lo, hi], labels without
// floating-point noise ("0.3", not "0.30000000000000004").
// Logarithmic (lo > 0): decades 10^k; over fewer decades also 2 and 5 x 10^k (below 2.3
// decades), 2, 3 and 5 x 10^k (below 1.3), every mantissa 1..9 (below 0.5); a range too narrow
// for two such ticks gets linear ones. Over more decades than `max_labels` only every 2nd, 3rd,
// 5th, 10th, 20th, 25th, 50th or 100th decade (the first step that leaves at most `max_labels`,
// at multiples of it: 10^-6, 10^-3, 10^0, ...) is labelled; the others stay as unlabelled ticks
// (grid lines) while there are at most 60 of them. Log labels are written compactly
// (compact_number): "0.01", "200", "1e-14", "2e5".
#pragma once

#include <string>
#include <vector>

namespace rheo::runtime::report {

struct Tick {
  double value = 0.0;
  std::string label;  // empty: a grid line without a label
};

std::vector<Tick> linear_ticks(double lo, double hi, int target = 6);
std::vector<Tick> log_ticks(double lo, double hi, int max_labels = 8);

// The 1-2-5 step closest to span / target.
double nice_step(double span, int target);

// VALUE to DIGITS significant digits, plain between 0.001 and 9999 ("0.5", "1000", "0.0123"),
// else with a short exponent ("1e4", "2e-14", "1.3e-9"); log ticks are labelled so (3 digits).
std::string compact_number(double value, int digits = 3);

}  // namespace rheo::runtime::report
