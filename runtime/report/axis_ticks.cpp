#include "runtime/report/axis_ticks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace rheo::runtime::report {
namespace {

// Six significant digits; an exponent without '+' or leading zeros ("1e-5", not "1e-05").
std::string label_of(double value) {
  if (value == 0.0) return "0";
  std::string text = fmt::format("{:.6g}", value);
  const std::size_t e = text.find('e');
  if (e == std::string::npos) return text;
  const bool negative = text[e + 1] == '-';
  std::size_t digits = e + 2;
  while (digits + 1 < text.size() && text[digits] == '0') ++digits;
  return text.substr(0, e + 1) + (negative ? "-" : "") + text.substr(digits);
}

constexpr int kMaxGridDecades = 60;

}  // namespace

double nice_step(double span, int target) {
  if (!(span > 0.0) || !std::isfinite(span)) return 1.0;
  const double raw = span / std::max(target, 1);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double mantissa = raw / magnitude;
  const double step = mantissa < 1.5 ? 1.0 : mantissa < 3.5 ? 2.0 : mantissa < 7.5 ? 5.0 : 10.0;
  return step * magnitude;
}

std::vector<Tick> linear_ticks(double lo, double hi, int target) {
  std::vector<Tick> ticks;
  if (!(hi > lo)) return {{lo, label_of(lo)}};
  const double step = nice_step(hi - lo, target);
  for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step; k += 1.0) {
    const double value = k * step;
    // Rounded to the step's decimals so that labels carry no floating-point noise.
    const double decimals = std::max(0.0, -std::floor(std::log10(step)));
    const double scale = std::pow(10.0, decimals);
    ticks.push_back({value, label_of(std::round(value * scale) / scale)});
  }
  return ticks;
}

std::string compact_number(double value, int digits) {
  if (value == 0.0 || !std::isfinite(value)) return label_of(value);
  int exponent = static_cast<int>(std::floor(std::log10(std::abs(value)) + 1e-12));
  if (exponent >= -3 && exponent <= 3) {
    const double scale = std::pow(10.0, digits - 1 - exponent);
    return label_of(std::round(value * scale) / scale);
  }
  const double scale = std::pow(10.0, digits - 1);
  double mantissa = std::round(value / std::pow(10.0, exponent) * scale) / scale;
  if (std::abs(mantissa) >= 10.0) mantissa /= 10.0, ++exponent;  // 9.996e5 to 3 digits: 1e6
  return fmt::format("{:.{}g}e{}", mantissa, digits, exponent);
}

std::vector<Tick> log_ticks(double lo, double hi, int max_labels) {
  if (!(lo > 0.0) || !(hi > lo)) return {{lo, compact_number(lo, 3)}};
  const double decades = std::log10(hi / lo);
  if (decades < 2.3) {
    const std::vector<int> mantissas = decades < 0.5   ? std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9}
                                       : decades < 1.3 ? std::vector<int>{1, 2, 3, 5}
                                                       : std::vector<int>{1, 2, 5};
    std::vector<Tick> ticks;
    for (int k = static_cast<int>(std::floor(std::log10(lo))); k <= static_cast<int>(std::ceil(std::log10(hi))); ++k)
      for (const int m : mantissas) {
        const double value = m * std::pow(10.0, k);
        if (value >= lo * (1.0 - 1e-9) && value <= hi * (1.0 + 1e-9)) ticks.push_back({value, compact_number(value, 3)});
      }
    if (ticks.size() < 2) return linear_ticks(lo, hi, 4);  // less than one mantissa step apart
    return ticks;
  }
  const int first = static_cast<int>(std::ceil(std::log10(lo) - 1e-9)), last = static_cast<int>(std::floor(std::log10(hi) + 1e-9));
  const auto labelled = [&](int step) {
    int n = 0;
    for (int k = first; k <= last; ++k) n += k % step == 0;
    return n;
  };
  int step = 1;
  for (const int candidate : {1, 2, 3, 5, 10, 20, 25, 50, 100}) {
    step = candidate;
    if (labelled(candidate) <= std::max(max_labels, 2)) break;
  }
  std::vector<Tick> ticks;
  const bool grid = last - first <= kMaxGridDecades;
  for (int k = first; k <= last; ++k) {
    const double value = std::pow(10.0, k);
    if (k % step == 0) ticks.push_back({value, compact_number(value, 3)});
    else if (grid) ticks.push_back({value, ""});
  }
  return ticks;
}

}  // namespace rheo::runtime::report
