#include "runtime/report/svg_text.hpp"

#include <fmt/format.h>

#include <cmath>

namespace rheo::runtime::report {

std::string escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string coordinate(double value) {
  const double rounded = std::round(value * 100.0) / 100.0;
  return fmt::format("{:g}", rounded == 0.0 ? 0.0 : rounded);
}

std::string svg_open(double width, double height, bool standalone, std::string_view title) {
  // Inline SVG in HTML needs no namespace: the page then names no URL at all.
  return fmt::format(
      "{}<svg{} viewBox=\"0 0 {} {}\" width=\"{}\" height=\"{}\" "
      "role=\"img\" aria-label=\"{}\" font-family=\"Helvetica, Arial, sans-serif\" font-size=\"13\">\n",
      standalone ? "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" : "", standalone ? " xmlns=\"http://www.w3.org/2000/svg\"" : "",
      coordinate(width), coordinate(height), coordinate(width), coordinate(height), escape(title));
}

const char* palette_color(int index) {
  static const char* const colors[] = {"#1f62a8", "#c8362c", "#2b8a3e", "#e07b00", "#7048a8", "#8a5a2b", "#c2408f", "#138a9e"};
  return colors[static_cast<unsigned>(index) % 8U];
}

}  // namespace rheo::runtime::report
