#include "runtime/report/element_symbols.hpp"

#include "runtime/report/svg_text.hpp"

#include <fmt/format.h>

namespace rheo::runtime::report {
namespace {

using lang::ElementKind;

constexpr double kSpring = 40, kDashpot = 36, kSlider = 36, kGap = 24, kInerter = 34, kSpringpot = 30, kJoin = 6;

std::string line(double x1, double y1, double x2, double y2) {
  return fmt::format("<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"/>", coordinate(x1), coordinate(y1), coordinate(x2), coordinate(y2));
}

std::string spring(double x, double cy) {
  std::string d = fmt::format("M{} {}h5", coordinate(x), coordinate(cy));
  for (int i = 0; i < 6; ++i) d += fmt::format("l2.5 {}l2.5 {}", i % 2 ? 8 : -8, i % 2 ? -8 : 8);
  d += "h5";
  return fmt::format("<path d=\"{}\" fill=\"none\"/>", d);
}

std::string dashpot(double x, double cy, bool quadratic) {
  std::string out = line(x, cy, x + 8, cy);
  out += fmt::format("<path d=\"M{0} {1}h-18v18h18\" fill=\"none\"/>", coordinate(x + 26), coordinate(cy - 9));
  out += line(x + 16, cy - 6, x + 16, cy + 6) + line(x + 16, cy, x + kDashpot, cy);
  if (quadratic) out += line(x + 20, cy - 6, x + 20, cy + 6);
  return out;
}

std::string slider(double x, double cy, bool smooth) {
  std::string out = line(x, cy, x + 8, cy);
  out += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"16\" height=\"13\" rx=\"{}\" fill=\"#e6e6e6\"/>", coordinate(x + 8), coordinate(cy - 6.5),
                     smooth ? 5 : 0);
  out += line(x + 4, cy + 8.5, x + 30, cy + 8.5) + line(x + 30, cy + 8.5, x + 30, cy) + line(x + 30, cy, x + kSlider, cy);
  for (int i = 0; i < 4; ++i) out += line(x + 7 + 6 * i, cy + 8.5, x + 4 + 6 * i, cy + 12);
  return out;
}

std::string gap(double x, double cy) {
  return line(x, cy, x + 8, cy) + fmt::format("<path d=\"M{0} {1}h4v16h-4\" fill=\"none\"/>", coordinate(x + 4), coordinate(cy - 8)) +
         fmt::format("<path d=\"M{0} {1}h-4v16h4\" fill=\"none\"/>", coordinate(x + 20), coordinate(cy - 8)) + line(x + 16, cy, x + kGap, cy);
}

std::string inerter(double x, double cy) {
  return line(x, cy, x + 6, cy) +
         fmt::format("<rect x=\"{}\" y=\"{}\" width=\"22\" height=\"18\" fill=\"none\"/>", coordinate(x + 6), coordinate(cy - 9)) +
         fmt::format("<path d=\"M{} {}l10 5l-10 5z\" fill=\"currentColor\"/>", coordinate(x + 12), coordinate(cy - 5)) +
         line(x + 28, cy, x + kInerter, cy);
}

std::string springpot(double x, double cy) {
  return line(x, cy, x + 5, cy) + fmt::format("<path d=\"M{} {}l10 -8l10 8l-10 8z\" fill=\"#e6e6e6\"/>", coordinate(x + 5), coordinate(cy)) +
         line(x + 25, cy, x + kSpringpot, cy);
}

}  // namespace

double symbol_length(ElementKind kind) {
  switch (kind) {
    case ElementKind::spring:
    case ElementKind::yeoh:
    case ElementKind::poly_spring: return kSpring;
    case ElementKind::dashpot:
    case ElementKind::quadratic_dashpot: return kDashpot;
    case ElementKind::maxwell: return kSpring + kJoin + kDashpot;
    case ElementKind::friction:
    case ElementKind::bouc_wen: return kSpring + kJoin + kSlider;
    case ElementKind::slider: return kSlider;
    case ElementKind::inerter: return kInerter;
    case ElementKind::gap: return kGap;
    case ElementKind::springpot: return kSpringpot;
    case ElementKind::parallel:
    case ElementKind::series: return 0;
  }
  return 0;
}

std::string symbol_svg(ElementKind kind, double x, double cy) {
  switch (kind) {
    case ElementKind::spring: return spring(x, cy);
    case ElementKind::yeoh:
    case ElementKind::poly_spring:
      return spring(x, cy) + line(x + 8, cy + 11, x + 32, cy - 11) +
             fmt::format("<path d=\"M{} {}l-6 1l3 4z\" fill=\"currentColor\"/>", coordinate(x + 33), coordinate(cy - 12));
    case ElementKind::dashpot: return dashpot(x, cy, false);
    case ElementKind::quadratic_dashpot: return dashpot(x, cy, true);
    case ElementKind::maxwell: return spring(x, cy) + line(x + kSpring, cy, x + kSpring + kJoin, cy) + dashpot(x + kSpring + kJoin, cy, false);
    case ElementKind::friction: return spring(x, cy) + line(x + kSpring, cy, x + kSpring + kJoin, cy) + slider(x + kSpring + kJoin, cy, false);
    case ElementKind::bouc_wen: return spring(x, cy) + line(x + kSpring, cy, x + kSpring + kJoin, cy) + slider(x + kSpring + kJoin, cy, true);
    case ElementKind::slider: return slider(x, cy, false);
    case ElementKind::inerter: return inerter(x, cy);
    case ElementKind::gap: return gap(x, cy);
    case ElementKind::springpot: return springpot(x, cy);
    case ElementKind::parallel:
    case ElementKind::series: return "";
  }
  return "";
}

}  // namespace rheo::runtime::report
