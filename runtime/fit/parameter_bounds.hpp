// Where a fitted value stands in its bounds, measured as the search sees it (fit.hpp): in
// z = ln p for a parameter whose bounds are positive, z = p otherwise.
#pragma once

#include "lang/model.hpp"

namespace rheo::runtime {

// A value this fraction of the bounds' width (in z) from a bound or closer is "at the bound":
// the search stops short of a bound by its tolerance and the last steps of a local method, so a
// value pressed against it rarely lands on it exactly (m.tau = 9999.93 ms of [0.01, 10000] ms
// is 5e-7 of the width from the upper bound). 1e-4 of six decades is 0.14 % of the value.
inline constexpr double kAtBoundFraction = 1e-4;

// True when the search runs over ln p for P: its bounds are positive.
bool logarithmic_search(const lang::Parameter& p);
// The search coordinate of VALUE for P: ln VALUE or VALUE.
double search_coordinate(const lang::Parameter& p, double value);

enum class BoundSide { none, lower, upper };
// Which bound of P (a parameter with bounds) VALUE is at, as defined above; none for a
// parameter without bounds or with an empty box.
BoundSide bound_reached(const lang::Parameter& p, double value);

}  // namespace rheo::runtime
