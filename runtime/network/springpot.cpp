#include "runtime/network/springpot.hpp"

#include <cmath>
#include <numbers>

namespace rheo::runtime {
namespace {

struct RelaxationRange {
  double lo, hi;  // s
};

RelaxationRange relaxation_range(double f_low, double f_high) {
  const double widen = std::pow(10.0, kSpringpotMarginDecades);
  return {1.0 / (2.0 * std::numbers::pi * f_high) / widen, widen / (2.0 * std::numbers::pi * f_low)};
}

int interior_modes(const RelaxationRange& r) { return static_cast<int>(std::ceil(kSpringpotModesPerDecade * std::log10(r.hi / r.lo) - 1e-9)); }

}  // namespace

int springpot_mode_count(double f_low, double f_high) { return interior_modes(relaxation_range(f_low, f_high)) + 2; }

void springpot_modes(const SpringpotParameters& p, std::span<double> stiffness, std::span<double> damping) {
  const RelaxationRange r = relaxation_range(p.f_low, p.f_high);
  const auto n = static_cast<int>(stiffness.size()) - 2;
  const double a = p.alpha;
  // H(l) = k sin(a pi)/pi (l/tau)^-a, written relative to tau so that no power overflows.
  const double scale = p.k * std::sin(a * std::numbers::pi) / std::numbers::pi;
  auto spectrum = [&](double l) { return scale * std::pow(l / p.tau, -a); };
  const double h = std::log(r.hi / r.lo) / n;
  for (int j = 0; j < n; ++j) {
    const double l = r.lo * std::exp((j + 0.5) * h);
    stiffness[static_cast<std::size_t>(j)] = spectrum(l) * h;
    damping[static_cast<std::size_t>(j)] = stiffness[static_cast<std::size_t>(j)] * l;
  }
  const auto slow = static_cast<std::size_t>(n), fast = slow + 1;
  stiffness[slow] = spectrum(r.hi) / a;
  damping[slow] = stiffness[slow] * r.hi * (1.0 + a) / a;
  damping[fast] = spectrum(r.lo) * r.lo / (1.0 - a);
  stiffness[fast] = damping[fast] / (r.lo * (1.0 - a) / (2.0 - a));
}

}  // namespace rheo::runtime
