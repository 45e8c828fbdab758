// A line/scatter plot as hand-written SVG: linear or logarithmic axes with ticks
// (axis_ticks.hpp), axis labels with units, grid, legend. Measured data are drawn as markers,
// model results as lines, an earlier model (before a diagnosis) as dashed lines; series of one
// group (e.g. one amplitude) share colour and marker shape, so measured and model of a group
// read as a pair. When a group has more than one style the legend says what each style means
// (Plot::meaning). Every series is one
// <g class="series" data-name="..." data-style="markers|line|dashed">, so that tests and scripts
// can count them. Non-finite points are skipped (a line breaks there); on a log axis so are
// values <= 0. A log axis with markers spans the markers and the lines at most a decade beyond
// them (a model far off the data, e.g. K' -> 0 at a phase of 90 deg, is clipped at the frame
// rather than squashing the data into a corner). The plot is 640 x 400 user units and scales to its container's width.
#pragma once

#include <string>
#include <vector>

namespace rheo::runtime::report {

enum class Scale { linear, log };

struct Axis {
  std::string label;  // with the unit: "frequency [Hz]"
  Scale scale = Scale::linear;
};

enum class SeriesStyle { markers, line, dashed };

struct Series {
  std::string name;   // "measured 0.2 mm"
  std::string group;  // legend entry: "0.2 mm"
  int color = 0;      // palette index; also selects the marker shape
  SeriesStyle style = SeriesStyle::line;
  std::vector<double> x, y;
};

struct Plot {
  std::string id;  // unique in the page: [A-Za-z0-9_-]
  std::string title;
  Axis x, y;
  std::vector<Series> series;
  // What each style stands for, in the legend's key (markers, line, dashed).
  std::string meaning[3] = {"measured", "model", "before"};  // at most ~14 characters: the legend column is narrow
};

// `standalone`: a complete SVG document (XML prolog, xmlns) for a file of its own; otherwise an
// <svg> element to inline in HTML.
std::string render_svg(const Plot& plot, bool standalone);

// Log when every value is positive and they span a factor of 20 or more, else linear.
Scale scale_for(const std::vector<double>& values);

}  // namespace rheo::runtime::report
