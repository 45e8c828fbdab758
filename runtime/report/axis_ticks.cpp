#include "runtime/report/axis_ticks.hpp"

#include <fmt/format.h>

#include <cmath>

namespace rheo::runtime::report {
namespace {

std::string label_of(double value) {
  if (value == 0.0) return "0";
  return fmt::format("{:.6g}", value);
}

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

std::vector<Tick> log_ticks(double lo, double hi) {
  std::vector<Tick> ticks;
  if (!(lo > 0.0) || !(hi > lo)) return {{lo, label_of(lo)}};
  const double decades = std::log10(hi / lo);
  const std::vector<int> mantissas = decades < 0.5   ? std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9}
                                     : decades < 1.3 ? std::vector<int>{1, 2, 3, 5}
                                     : decades < 2.3 ? std::vector<int>{1, 2, 5}
                                                     : std::vector<int>{1};
  for (int k = static_cast<int>(std::floor(std::log10(lo))); k <= static_cast<int>(std::ceil(std::log10(hi))); ++k)
    for (const int m : mantissas) {
      const double value = m * std::pow(10.0, k);
      if (value >= lo * (1.0 - 1e-9) && value <= hi * (1.0 + 1e-9)) ticks.push_back({value, label_of(value)});
    }
  if (ticks.size() < 2) return linear_ticks(lo, hi, 4);  // less than one mantissa step apart
  return ticks;
}

}  // namespace rheo::runtime::report
