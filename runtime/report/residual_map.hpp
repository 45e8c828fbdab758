// A residual map: the measured grid of a harmonic data set, frequency across and amplitude up,
// one cell per point, coloured on a diverging scale symmetric about zero (blue: model below
// the data, red: above, white: agreement), with a colour-scale legend. The scale ends at the
// smallest 1-2-5 value >= the largest |residual|. Each cell is <rect class="cell"
// data-amplitude data-frequency data-value> with a <title> tooltip; grid positions without a
// point stay grey. Amplitude and frequency rows/columns are the distinct values, in order.
#pragma once

#include <string>
#include <vector>

namespace rheo::runtime::report {

struct ResidualMap {
  std::string title;                                // "Stiffness residual"
  std::string unit;                                 // of the values: "%", "deg"
  std::vector<double> amplitude, frequency, value;  // mm, Hz, in `unit`; one per point
  double limit = 0.0;                               // end of the colour scale; 0: color_scale_limit(value). Maps to compare share one.
};

std::string render_residual_map(const ResidualMap& map, bool standalone);

// The end of the colour scale: the smallest 1, 2 or 5 x 10^k >= largest |value| (1 when all are 0).
double color_scale_limit(const std::vector<double>& values);

// Fill colour "#rrggbb" of value v on the scale [-limit, limit].
std::string diverging_color(double v, double limit);

}  // namespace rheo::runtime::report
