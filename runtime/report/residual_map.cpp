#include "runtime/report/residual_map.hpp"

#include "runtime/report/axis_ticks.hpp"
#include "runtime/report/svg_text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace rheo::runtime::report {
namespace {

constexpr double kWidth = 640, kHeight = 400;
constexpr double kLeft = 74, kRight = 118, kTop = 34, kBottom = 52;
constexpr double kGridWidth = kWidth - kLeft - kRight, kGridHeight = kHeight - kTop - kBottom;

// Distinct values in increasing order (equal within 1e-9 relative).
std::vector<double> distinct(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end(), [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b)); }), v.end());
  return v;
}

std::size_t index_of(const std::vector<double>& values, double v) {
  const auto it = std::lower_bound(values.begin(), values.end(), v * (1.0 - 1e-9));
  return static_cast<std::size_t>(it - values.begin());
}

// Every k-th label, so that labels are at least `spacing` user units apart.
std::size_t label_stride(std::size_t count, double extent, double spacing) {
  return std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(spacing * static_cast<double>(count) / extent)));
}

std::vector<std::string> labels_of(const std::vector<double>& values) {
  std::vector<std::string> out;
  for (const double v : values) out.push_back(compact_number(v, 3));
  return out;
}

// Room a row of labels needs per label at font size 13: ~7.5 user units a character and a gap.
double label_room(const std::vector<std::string>& labels) {
  std::size_t longest = 0;
  for (const std::string& l : labels) longest = std::max(longest, l.size());
  return 7.5 * static_cast<double>(longest) + 10.0;
}

std::string color_bar(double limit, const std::string& unit) {
  const double x = kLeft + kGridWidth + 22, width = 18;
  const int steps = 21;
  const double step_height = kGridHeight / steps;
  std::string out = "<g class=\"color-scale\">";
  for (int i = 0; i < steps; ++i) {
    const double v = limit * (1.0 - 2.0 * (i + 0.5) / steps);
    out += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\"/>", x, coordinate(kTop + i * step_height), width,
                       coordinate(step_height + 0.5), diverging_color(v, limit));
  }
  out += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#444\"/>", x, kTop, width, kGridHeight);
  for (const double f : {1.0, 0.5, 0.0, -0.5, -1.0}) {
    const double y = kTop + kGridHeight * (1.0 - f) / 2.0;
    out += fmt::format("<text x=\"{}\" y=\"{}\">{}{:g}</text>", x + width + 5, coordinate(y + 4.5), f > 0 ? "+" : "", f * limit);
  }
  out += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">[{}]</text>", x + width / 2, kTop - 8, escape(unit));
  return out + "</g>\n";
}

}  // namespace

double color_scale_limit(const std::vector<double>& values) {
  double largest = 0.0;
  for (const double v : values)
    if (std::isfinite(v)) largest = std::max(largest, std::abs(v));
  if (largest == 0.0) return 1.0;
  double limit = std::pow(10.0, std::floor(std::log10(largest)));
  for (const double m : {1.0, 2.0, 5.0, 10.0})
    if (m * limit >= largest * (1.0 - 1e-12)) return m * limit;
  return 10.0 * limit;
}

std::string diverging_color(double v, double limit) {
  const double t = std::isfinite(v) ? std::clamp(v / limit, -1.0, 1.0) : 0.0;
  const double white[3] = {247, 247, 247}, blue[3] = {33, 102, 172}, red[3] = {178, 24, 43};
  const double* end = t < 0 ? blue : red;
  const double a = std::abs(t);
  int rgb[3];
  for (int k = 0; k < 3; ++k) rgb[k] = static_cast<int>(std::lround(white[k] + a * (end[k] - white[k])));
  return fmt::format("#{:02x}{:02x}{:02x}", rgb[0], rgb[1], rgb[2]);
}

std::string render_residual_map(const ResidualMap& map, bool standalone) {
  const std::vector<double> frequencies = distinct(map.frequency), amplitudes = distinct(map.amplitude);
  const double limit = map.limit > 0.0 ? map.limit : color_scale_limit(map.value);
  const double cw = kGridWidth / static_cast<double>(std::max<std::size_t>(frequencies.size(), 1));
  const double ch = kGridHeight / static_cast<double>(std::max<std::size_t>(amplitudes.size(), 1));
  std::string out = svg_open(kWidth, kHeight, standalone, map.title);
  out += fmt::format("<rect width=\"{}\" height=\"{}\" fill=\"#fff\"/>\n", kWidth, kHeight);
  out += fmt::format("<text class=\"title\" x=\"{}\" y=\"21\" font-size=\"15\" font-weight=\"bold\">{}</text>\n", kLeft, escape(map.title));
  out += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#bdbdbd\"/>\n<g class=\"cells\" stroke=\"#fff\" stroke-width=\"0.5\">",
                     kLeft, kTop, kGridWidth, kGridHeight);
  for (std::size_t i = 0; i < map.value.size() && i < map.amplitude.size() && i < map.frequency.size(); ++i) {
    const double x = kLeft + cw * static_cast<double>(index_of(frequencies, map.frequency[i]));
    const double y = kTop + kGridHeight - ch * static_cast<double>(index_of(amplitudes, map.amplitude[i]) + 1);
    out += fmt::format(
        "<rect class=\"cell\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\" data-amplitude=\"{:g}\" "
        "data-frequency=\"{:g}\" data-value=\"{:.4g}\"><title>{:g} mm, {:g} Hz: {:+.3g} {}</title></rect>",
        coordinate(x), coordinate(y), coordinate(cw), coordinate(ch), diverging_color(map.value[i], limit), map.amplitude[i], map.frequency[i],
        map.value[i], map.amplitude[i], map.frequency[i], map.value[i], escape(map.unit));
  }
  out += "</g>\n<g class=\"tick-labels\" fill=\"#222\">";
  const std::vector<std::string> frequency_labels = labels_of(frequencies), amplitude_labels = labels_of(amplitudes);
  for (std::size_t j = 0; j < frequencies.size(); j += label_stride(frequencies.size(), kGridWidth, label_room(frequency_labels)))
    out += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>", coordinate(kLeft + cw * (static_cast<double>(j) + 0.5)),
                       kTop + kGridHeight + 17, frequency_labels[j]);
  for (std::size_t j = 0; j < amplitudes.size(); j += label_stride(amplitudes.size(), kGridHeight, 16))
    out += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>", kLeft - 6,
                       coordinate(kTop + kGridHeight - ch * (static_cast<double>(j) + 0.5) + 4.5), amplitude_labels[j]);
  out += "</g>\n";
  out += fmt::format("<text class=\"axis-label\" x=\"{}\" y=\"{}\" text-anchor=\"middle\">frequency [Hz]</text>\n",
                     coordinate(kLeft + kGridWidth / 2), kHeight - 12);
  out += fmt::format("<text class=\"axis-label\" transform=\"translate(16 {}) rotate(-90)\" text-anchor=\"middle\">amplitude [mm]</text>\n",
                     coordinate(kTop + kGridHeight / 2));
  return out + color_bar(limit, map.unit) + "</svg>\n";
}

}  // namespace rheo::runtime::report
