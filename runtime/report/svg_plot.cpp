#include "runtime/report/svg_plot.hpp"

#include "runtime/report/axis_ticks.hpp"
#include "runtime/report/svg_text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rheo::runtime::report {
namespace {

constexpr double kWidth = 640, kHeight = 400;
constexpr double kLeft = 74, kRight = 138, kTop = 34, kBottom = 52;
constexpr double kPlotWidth = kWidth - kLeft - kRight, kPlotHeight = kHeight - kTop - kBottom;

bool usable(double v, Scale scale) { return std::isfinite(v) && (scale == Scale::linear || v > 0.0); }

// Data range of an axis, widened a little so that markers do not sit on the frame.
struct Range {
  double lo = 0.0, hi = 1.0;
  Scale scale = Scale::linear;
  double fraction(double v) const { return scale == Scale::log ? std::log(v / lo) / std::log(hi / lo) : (v - lo) / (hi - lo); }
};

Range range_of(const Plot& plot, bool x_axis) {
  const Scale scale = x_axis ? plot.x.scale : plot.y.scale;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Series& s : plot.series)
    for (const double v : x_axis ? s.x : s.y)
      if (usable(v, scale)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!std::isfinite(lo)) return {scale == Scale::log ? 1.0 : 0.0, scale == Scale::log ? 10.0 : 1.0, scale};
  if (scale == Scale::log) {
    // Measured markers set the range; a line reaches a decade beyond them at most, and is clipped there.
    double marker_lo = std::numeric_limits<double>::infinity(), marker_hi = -marker_lo;
    for (const Series& s : plot.series)
      if (s.style == SeriesStyle::markers)
        for (const double v : x_axis ? s.x : s.y)
          if (usable(v, scale)) marker_lo = std::min(marker_lo, v), marker_hi = std::max(marker_hi, v);
    if (std::isfinite(marker_lo)) lo = std::max(lo, marker_lo / 10.0), hi = std::min(hi, marker_hi * 10.0);
    if (hi <= lo) return {lo / 2.0, hi * 2.0, scale};
    const double pad = std::pow(hi / lo, 0.04);
    return {lo / pad, hi * pad, scale};
  }
  if (hi <= lo) {
    const double half = lo == 0.0 ? 1.0 : 0.1 * std::abs(lo);
    return {lo - half, hi + half, scale};
  }
  const double pad = 0.05 * (hi - lo);
  return {lo - pad, hi + pad, scale};
}

std::vector<Tick> ticks_of(const Range& r) { return r.scale == Scale::log ? log_ticks(r.lo, r.hi) : linear_ticks(r.lo, r.hi, 6); }

// The marker of palette index `color` centred on (x, y): circle, square, triangle or diamond
// (index mod 4), so that groups stay apart in black-and-white print.
std::string marker(int color, double x, double y) {
  const double r = 3.6;
  switch (static_cast<unsigned>(color) % 4U) {
    case 0: return fmt::format("M{} {}a{} {} 0 1 0 {} 0a{} {} 0 1 0 {} 0", coordinate(x - r), coordinate(y), r, r, 2 * r, r, r, -2 * r);
    case 1: return fmt::format("M{} {}h{}v{}h{}z", coordinate(x - r), coordinate(y - r), 2 * r, 2 * r, -2 * r);
    case 2: return fmt::format("M{} {}l{} {}h{}z", coordinate(x), coordinate(y - 1.2 * r), 1.2 * r, 2.1 * r, -2.4 * r);
    default:
      return fmt::format("M{} {}l{} {}l{} {}l{} {}z", coordinate(x), coordinate(y - 1.3 * r), 1.3 * r, 1.3 * r, -1.3 * r, 1.3 * r, -1.3 * r,
                         -1.3 * r);
  }
}

const char* style_name(SeriesStyle style) {
  switch (style) {
    case SeriesStyle::markers: return "markers";
    case SeriesStyle::line: return "line";
    default: return "dashed";
  }
}

std::string line_svg(double x, double y, const char* color, SeriesStyle style) {
  return fmt::format("<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"{}\" stroke-width=\"1.8\"{}/>", x, y, x + 22, y, color,
                     style == SeriesStyle::dashed ? " stroke-dasharray=\"5 3\"" : "");
}

std::string series_svg(const Series& s, const Range& xr, const Range& yr) {
  std::string out = fmt::format("<g class=\"series\" data-name=\"{}\" data-style=\"{}\">", escape(s.name), style_name(s.style));
  const char* color = palette_color(s.color);
  std::string path;
  bool pen_down = false;
  for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
    if (!usable(s.x[i], xr.scale) || !usable(s.y[i], yr.scale)) {
      pen_down = false;
      continue;
    }
    const double x = kLeft + kPlotWidth * xr.fraction(s.x[i]);
    const double y = kTop + kPlotHeight * (1.0 - yr.fraction(s.y[i]));
    if (s.style == SeriesStyle::markers) {
      path += marker(s.color, x, y);
    } else {
      path += fmt::format("{}{} {}", pen_down ? "L" : "M", coordinate(x), coordinate(y));
      pen_down = true;
    }
  }
  if (s.style == SeriesStyle::markers)
    out += fmt::format("<path d=\"{}\" fill=\"{}\" fill-opacity=\"0.8\" stroke=\"{}\" stroke-width=\"0.8\"/>", path, color, color);
  else
    out += fmt::format("<path d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" stroke-linejoin=\"round\"{}/>", path, color,
                       s.style == SeriesStyle::dashed ? "1.5" : "1.8", s.style == SeriesStyle::dashed ? " stroke-dasharray=\"6 4\"" : "");
  return out + "</g>\n";
}

// An unlabelled tick (a decade between labelled ones) is a fainter grid line.
const char* grid_style(const Tick& t) { return t.label.empty() ? " stroke=\"#eeeeee\"" : ""; }

std::string axes_svg(const Plot& plot, const Range& xr, const Range& yr) {
  std::string out = "<g class=\"axes\" stroke=\"#d9d9d9\" stroke-width=\"1\">";
  std::string labels = "<g class=\"tick-labels\" fill=\"#222\">";
  for (const Tick& t : ticks_of(xr)) {
    const double x = kLeft + kPlotWidth * xr.fraction(t.value);
    out += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\"{3}/>", coordinate(x), kTop, kTop + kPlotHeight, grid_style(t));
    if (!t.label.empty())
      labels += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>", coordinate(x), kTop + kPlotHeight + 17, escape(t.label));
  }
  for (const Tick& t : ticks_of(yr)) {
    const double y = kTop + kPlotHeight * (1.0 - yr.fraction(t.value));
    out += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\"{3}/>", kLeft, coordinate(y), kLeft + kPlotWidth, grid_style(t));
    if (!t.label.empty())
      labels += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>", kLeft - 6, coordinate(y + 4), escape(t.label));
  }
  out += "</g>\n" + labels + "</g>\n";
  out += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#444\"/>\n", kLeft, kTop, kPlotWidth, kPlotHeight);
  out += fmt::format("<text class=\"axis-label\" x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}{}</text>\n", coordinate(kLeft + kPlotWidth / 2),
                     kHeight - 12, escape(plot.x.label), plot.x.scale == Scale::log ? " (log)" : "");
  out += fmt::format("<text class=\"axis-label\" transform=\"translate(16 {}) rotate(-90)\" text-anchor=\"middle\">{}{}</text>\n",
                     coordinate(kTop + kPlotHeight / 2), escape(plot.y.label), plot.y.scale == Scale::log ? " (log)" : "");
  return out;
}

std::string legend_svg(const Plot& plot) {
  struct Entry {
    const Series* first;
    bool has[3] = {false, false, false};  // by SeriesStyle
  };
  std::vector<Entry> groups;
  bool has_style[3] = {false, false, false};
  bool paired = false;  // some group has two styles: explain them
  for (const Series& s : plot.series) {
    auto it = std::find_if(groups.begin(), groups.end(), [&](const Entry& g) { return g.first->group == s.group; });
    if (it == groups.end()) it = groups.insert(groups.end(), Entry{&s});
    const auto style = static_cast<std::size_t>(s.style);
    it->has[style] = has_style[style] = true;
    paired = paired || (it->has[0] + it->has[1] + it->has[2] > 1);
  }
  std::string out = "<g class=\"legend\">";
  const double x = kLeft + kPlotWidth + 14;
  double y = kTop + 8;
  for (const Entry& g : groups) {
    const char* color = palette_color(g.first->color);
    if (g.has[1] || g.has[2]) out += line_svg(x, y, color, g.has[1] ? SeriesStyle::line : SeriesStyle::dashed);
    if (g.has[0]) out += fmt::format("<path d=\"{}\" fill=\"{}\" stroke=\"{}\"/>", marker(g.first->color, x + 11, y), color, color);
    out += fmt::format("<text x=\"{}\" y=\"{}\">{}</text>", x + 28, coordinate(y + 4.5), escape(g.first->group));
    y += 19;
  }
  if (paired) {
    y += 8;
    for (const SeriesStyle style : {SeriesStyle::markers, SeriesStyle::line, SeriesStyle::dashed}) {
      const auto k = static_cast<std::size_t>(style);
      if (!has_style[k]) continue;
      out += fmt::format("<text x=\"{}\" y=\"{}\" fill=\"#444\">{}: {}</text>", x, coordinate(y + 4.5), style_name(style), escape(plot.meaning[k]));
      y += 17.5;
    }
  }
  return out + "</g>\n";
}

}  // namespace

Scale scale_for(const std::vector<double>& values) {
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (const double v : values) {
    if (!std::isfinite(v)) continue;
    if (v <= 0.0) return Scale::linear;
    lo = std::min(lo, v), hi = std::max(hi, v);
  }
  return std::isfinite(lo) && hi / lo >= 20.0 ? Scale::log : Scale::linear;
}

std::string render_svg(const Plot& plot, bool standalone) {
  const Range xr = range_of(plot, true), yr = range_of(plot, false);
  std::string out = svg_open(kWidth, kHeight, standalone, plot.title);
  out += fmt::format("<defs><clipPath id=\"clip-{}\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/></clipPath></defs>\n", escape(plot.id),
                     kLeft, kTop, kPlotWidth, kPlotHeight);
  out += fmt::format("<rect width=\"{}\" height=\"{}\" fill=\"#fff\"/>\n", kWidth, kHeight);
  out += fmt::format("<text class=\"title\" x=\"{}\" y=\"21\" font-size=\"15\" font-weight=\"bold\">{}</text>\n", kLeft, escape(plot.title));
  out += axes_svg(plot, xr, yr);
  out += fmt::format("<g clip-path=\"url(#clip-{})\">\n", escape(plot.id));
  for (const Series& s : plot.series)
    if (s.style != SeriesStyle::markers) out += series_svg(s, xr, yr);
  for (const Series& s : plot.series)  // markers over lines
    if (s.style == SeriesStyle::markers) out += series_svg(s, xr, yr);
  out += "</g>\n" + legend_svg(plot) + "</svg>\n";
  return out;
}

}  // namespace rheo::runtime::report
