// Text pieces shared by the hand-written SVG and HTML of reports: escaping for XML/HTML text and
// attribute values, compact coordinates, and the series palette (readable on screen and, with
// distinct marker shapes, in black-and-white print).
#pragma once

#include <string>
#include <string_view>

namespace rheo::runtime::report {

// Escapes &, <, >, " and ' so that any text (element paths, file names) is safe in element
// content and in double- or single-quoted attribute values.
std::string escape(std::string_view text);

// A coordinate in user units with at most two decimals ("12.5", "-3").
std::string coordinate(double value);

// The opening <svg> tag of a figure of width x height user units that scales to its container;
// `standalone` prefixes the XML prolog and the namespace for a file of its own. `title` is the
// accessible name (escaped here).
std::string svg_open(double width, double height, bool standalone, std::string_view title);

// Colour of series group `index` (cycles through 8 colours).
const char* palette_color(int index);

}  // namespace rheo::runtime::report
