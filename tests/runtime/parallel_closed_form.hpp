// The exact steady state of a parallel network of an elastic branch, Maxwell arms and friction
// elements under u = u0 sin(w t), composed by hand from the element laws (thesis eqs. 1.2,
// 5.26, 5.27, B.58, C.13, C.20): the tests' own closed form, independent of runtime/closed_form.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <numbers>
#include <vector>

namespace rheo::test {

// K* of a Maxwell element k [N/mm], tau [s] at f [Hz]: k i w tau / (1 + i w tau).
inline std::complex<double> maxwell(double k, double tau, double f) {
  const std::complex<double> iwt{0.0, 2 * std::numbers::pi * f * tau};
  return k * iwt / (1.0 + iwt);
}

// Thesis measures (eqs. 1.2, 5.26, 5.27) of the exact steady state of a parallel network of an
// elastic branch Y(u), Maxwell arms (k, tau) and friction elements (k, uy), under
// u = u0 sin(theta), composed by hand from the element laws:
//   loading half theta in [-pi/2, pi/2]: F = Y(u) + sum u0 (K' sin theta + K'' cos theta)
//     + sum_friction (u0 <= uy ? k u : min(k uy, -k uy + k (u + u0)));
//   the unloading half mirrors it, so F^ = max |F| over the loading half (found by sampling and
//   a golden-section polish); U = pi u0^2 sum K'' + sum_{u0 > uy} 4 k uy (u0 - uy) (C.13, C.20).
struct Arm {
  double k, tau;
};
struct Slip {
  double k, uy;
};
struct Measures {
  double stiffness, phase;  // N/mm, rad
};
inline Measures parallel_closed_form(const std::function<double(double)>& elastic, const std::vector<Arm>& arms, const std::vector<Slip>& frictions,
                                     double u0, double f) {
  double k1 = 0.0, k2 = 0.0;  // K', K'' of the Maxwell arms
  for (const auto& a : arms) {
    const std::complex<double> k = maxwell(a.k, a.tau, f);
    k1 += k.real();
    k2 += k.imag();
  }
  const auto force = [&](double theta) {
    const double u = u0 * std::sin(theta);
    double F = elastic(u) + u0 * (k1 * std::sin(theta) + k2 * std::cos(theta));
    for (const auto& s : frictions) F += u0 <= s.uy ? s.k * u : std::min(s.k * s.uy, -s.k * s.uy + s.k * (u + u0));
    return std::abs(F);
  };
  const int n = 20000;
  const double h = std::numbers::pi / n;
  int best = 0;
  for (int i = 1; i <= n; ++i)
    if (force(-std::numbers::pi / 2 + i * h) > force(-std::numbers::pi / 2 + best * h)) best = i;
  double a = -std::numbers::pi / 2 + (best - 1) * h, b = a + 2 * h;
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 80; ++i) {
    const double x1 = b - g * (b - a), x2 = a + g * (b - a);
    (force(x1) < force(x2) ? a : b) = (force(x1) < force(x2) ? x1 : x2);
  }
  const double amplitude = std::max(force(-std::numbers::pi / 2 + best * h), force((a + b) / 2));
  double energy = std::numbers::pi * u0 * u0 * k2;
  for (const auto& s : frictions)
    if (u0 > s.uy) energy += 4 * s.k * s.uy * (u0 - s.uy);
  return {amplitude / u0, std::asin(energy / (std::numbers::pi * amplitude * u0))};
}

}  // namespace rheo::test
