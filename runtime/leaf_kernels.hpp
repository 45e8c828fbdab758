// Step relations of the leaf elements under a piecewise-linear elongation history.
//
// Over one step of length dt the elongation of a leaf changes by de at constant rate de/dt.
// Each relation maps de to the force at the end of the step, F(de), and its slope dF/dde.
// All are monotone non-decreasing in de, which the series/parallel solver relies on.
// Units: force N, elongation mm, time s, stiffness N/mm, damping N*s/mm.
#pragma once

#include <algorithm>
#include <cmath>

namespace rheo::runtime {

struct ForceSlope {
  double force;  // N
  double slope;  // N/mm
};

// Maxwell element (spring k in series with dashpot c, tau = c/k), eq. 2.3:
//   dF/dt + F/tau = k de/dt.
// Exact solution for constant de/dt over the step (eq. 2.7 with the integral evaluated exactly
// rather than by the trapezoidal rule of 2.2):
//   F_{n+1} = a F_n + b de,  a = exp(-dt/tau),  b = k tau (1 - a) / dt = c (1 - a) / dt.
// Stable for any dt/tau: 0 <= a < 1 and 0 < b <= k. As k -> inf (tau -> 0) it tends to the
// dashpot relation F = c de/dt.
struct MaxwellStep {
  double a;  // decay over the step
  double b;  // N/mm
  static MaxwellStep make(double k, double c, double dt) {
    const double tau = c / k;
    const double x = dt / tau;
    const double a = std::exp(-x);
    // (1 - a)/x loses accuracy for tiny x: use its series there.
    const double one_minus_a_over_x = x < 1e-5 ? 1.0 - x / 2.0 + x * x / 6.0 : -std::expm1(-x) / x;
    return {a, k * one_minus_a_over_x};
  }
  ForceSlope operator()(double force_before, double de) const { return {a * force_before + b * de, b}; }
};

// Dashpot F = c de/dt: the exact (constant) force over a step of constant rate.
inline ForceSlope dashpot_step(double c_over_dt, double de) { return {c_over_dt * de, c_over_dt}; }

// Elastoplastic friction element (spring k in series with a slider slipping at |F| = fy),
// return mapping of section 2.4, eq. 2.9: trial F_n + k de, scaled back to +-fy.
// Exact for a monotone elongation increment.
inline ForceSlope friction_step(double k, double fy, double force_before, double de) {
  const double trial = force_before + k * de;
  if (trial > fy) return {fy, 0.0};
  if (trial < -fy) return {-fy, 0.0};
  return {trial, k};
}

// Yeoh spring, eq. 3.3: F = 2 (D10 + 2 D20 e^2 + 3 D30 e^4) e = 2 D10 e + 4 D20 e^3 + 6 D30 e^5,
// dF/de = 2 D10 + 12 D20 e^2 + 30 D30 e^4.
struct YeohLaw {
  double d10, d20, d30;  // N/mm, N/mm^3, N/mm^5
  double force(double e) const {
    const double e2 = e * e;
    return e * (2.0 * d10 + e2 * (4.0 * d20 + 6.0 * d30 * e2));
  }
  double slope(double e) const {
    const double e2 = e * e;
    return 2.0 * d10 + e2 * (12.0 * d20 + 30.0 * d30 * e2);
  }
};

}  // namespace rheo::runtime
