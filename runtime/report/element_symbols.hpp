// The drawing of one leaf element of a network diagram: the usual rheological symbol of its
// kind on a horizontal wire at height cy (user units, stroke colour inherited):
//   spring: zigzag; yeoh: zigzag crossed by an arrow (non-linear); dashpot: cylinder and
//   piston; quadratic_dashpot: cylinder with a double piston; maxwell: spring + dashpot;
//   friction: spring + slider; slider: a block on a hatched surface; bouc_wen: spring + a
//   rounded (smooth) slider; inerter: a box holding a flywheel triangle; gap: two facing
//   stops; springpot: a rhombus.
#pragma once

#include "lang/model.hpp"

#include <string>

namespace rheo::runtime::report {

// Length [user units] of the symbol of a leaf kind along the wire.
double symbol_length(lang::ElementKind kind);

// SVG of the symbol starting at x (ending at x + symbol_length(kind)), centred on cy; extends at
// most 12 units above and below cy.
std::string symbol_svg(lang::ElementKind kind, double x, double cy);

}  // namespace rheo::runtime::report
