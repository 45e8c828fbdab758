// Step relations of the leaf elements under a piecewise-linear elongation history.
//
// Over one step of length dt the elongation of a leaf changes by de at constant rate de/dt.
// Each relation maps de to the force at the end of the step, F(de), and its slope dF/dde.
// All are monotone non-decreasing in de, which the series/parallel solver relies on.
// Exact for that history except the inerter, whose force is the acceleration's (a sum of
// impulses at the kinks of a piecewise-linear history): its relations are second order.
// Units: force N, elongation mm, time s, stiffness N/mm, damping N*s/mm, inertance
// N*s^2/mm, quadratic damping N*s^2/mm^2. bouc_wen: runtime/network/bouc_wen.hpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

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

// Storage and loss stiffness [N/mm] of a Maxwell element k at x = omega tau (0 <= x), from
//   K* = k i x / (1 + i x):  K' = k x^2 / (1 + x^2),  K'' = k x / (1 + x^2),   (eq. 5.11, B.58)
// written as sums of positive terms (no cancellation) in which neither x^2 nor 1/x^2 appears
// beside a 1 it would swamp or overflow: with r = min(x, 1/x) and d = 1 + r^2,
//   x <= 1:  K' = k x (x / d),  K'' = k x / d;     x > 1:  K' = k / d,  K'' = k r / d.
// Each is within a few ulp for every x from 0 to the largest double (omega tau spans 1e-41 to
// 1e41 within lang/limits.hpp's frequencies and the relaxation times of a master curve).
struct StorageLoss {
  double storage;  // N/mm
  double loss;     // N/mm
};
inline StorageLoss maxwell_storage_loss(double k, double x) {
  if (x <= 1.0) {
    const double q = x / (1.0 + x * x);
    return {k * x * q, k * q};
  }
  const double r = 1.0 / x, d = 1.0 + r * r;
  return {k / d, k * (r / d)};
}

// Dashpot F = c de/dt: the exact (constant) force over a step of constant rate.
inline ForceSlope dashpot_step(double c_over_dt, double de) { return {c_over_dt * de, c_over_dt}; }

// Quadratic dashpot F = cq |de/dt| de/dt, exact for a constant rate over the step, with
// q = cq/dt^2 [N/mm^2]: F = q |de| de, dF/dde = 2 q |de|. Inverse de = sgn(F) sqrt(|F|/q),
// dde/dF = 1 / (2 sqrt(q |F|)) (infinite at F = 0: solve_monotone bisects there).
inline ForceSlope quadratic_dashpot_step(double q, double de) { return {q * std::abs(de) * de, 2.0 * q * std::abs(de)}; }
inline ForceSlope quadratic_dashpot_inverse(double q, double force) {
  const double root = std::sqrt(std::abs(force) / q);
  return {std::copysign(root, force), 0.5 / (q * root)};
}

// Inerter F = b d2e/dt2 driven through a compliant member (an integrator of the force):
// Newmark's average-acceleration (trapezoidal) rule, second order, unconditionally stable, no
// numerical damping. With v_n and a_n = F_n/b at the step start and m = 4 b/dt^2 [N/mm]:
//   a_{n+1} = 4 (de - dt v_n)/dt^2 - a_n,  F = m (de - dt v_n) - F_n,  dF/dde = m,
//   inverse de = dt v_n + (F + F_n)/m,     after the step v_{n+1} = 2 de/dt - v_n.
struct InerterStep {
  double m;   // 4 b/dt^2 [N/mm]
  double dt;  // s
  ForceSlope operator()(double force_before, double velocity_before, double de) const {
    return {m * (de - dt * velocity_before) - force_before, m};
  }
  ForceSlope inverse(double force_before, double velocity_before, double force) const {
    return {dt * velocity_before + (force + force_before) / m, 1.0 / m};
  }
  double velocity_after(double velocity_before, double de) const { return 2.0 * de / dt - velocity_before; }
};

// Inerter whose elongation is the drive (root block). Newmark would differentiate the drive
// twice through a double pole at z = -1 (an alternating error that grows linearly), so here
// the acceleration at the step end is the derivative of the quadratic through the mean rates
// of the last three steps, each at its step's midpoint: r (this step, length dt, at +dt/2),
// r0 (length h0, at -h0/2) and r1 (length h1, at -h0 - h1/2), times from the step start:
//   d2e/dt2 (dt) = w r + w0 r0 + w1 r1,  w + w0 + w1 = 0,
// second order in the step (uniform steps: (2 r - 3 r0 + r1)/dt, error (11/12) dt^2 e''''),
// and a finite impulse response, hence stable: a kink of the drive (a rate change dr) gives a
// force pulse of total impulse b dr over the next two steps. h0, h1 = 0 (at rest before the
// drive began) are taken as the step before, or dt.
// A step may be the first part of a longer linear piece of the drive (the harmonic protocol's
// midpoint probe, `piece` = 2 dt): the rate is then the piece's, sampled at piece/2, and the
// relation still estimates d2e/dt2 at the step end to second order.
struct PrescribedInerter {
  double w, w0, w1;  // 1/s
  static PrescribedInerter make(double dt, double piece, double h0, double h1) {
    if (!(h0 > 0.0)) h0 = piece;
    if (!(h1 > 0.0)) h1 = h0;
    const double x = 0.5 * piece, x0 = -0.5 * h0, x1 = -h0 - 0.5 * h1, t = dt;
    return {((t - x0) + (t - x1)) / ((x - x0) * (x - x1)), ((t - x) + (t - x1)) / ((x0 - x) * (x0 - x1)),
            ((t - x) + (t - x0)) / ((x1 - x) * (x1 - x0))};
  }
  // Force of inertance b for an increment de over dt, after mean rates r0, r1.
  ForceSlope operator()(double b, double dt, double r0, double r1, double de) const { return {b * (w * de / dt + w0 * r0 + w1 * r1), b * w / dt}; }
};

// Elastoplastic friction element (spring k in series with a slider slipping at |F| = fy),
// return mapping of section 2.4, eq. 2.9: trial F_n + k de, scaled back to +-fy.
// Exact for a monotone elongation increment.
inline ForceSlope friction_step(double k, double fy, double force_before, double de) {
  const double trial = force_before + k * de;
  if (trial > fy) return {fy, 0.0};
  if (trial < -fy) return {-fy, 0.0};
  return {trial, k};
}
// The same with one-sided yield forces: slipping at F = fy_pos in tension and F = -fy_neg in
// compression (fy_pos, fy_neg > 0 [N]).
inline ForceSlope friction_step(double k, double fy_pos, double fy_neg, double force_before, double de) {
  const double trial = force_before + k * de;
  if (trial > fy_pos) return {fy_pos, 0.0};
  if (trial < -fy_neg) return {-fy_neg, 0.0};
  return {trial, k};
}

// The centre [mm] of a gap's play as the kernels take it: its `center` within +-width/2, so that
// the rest position e = 0 lies in the play (a written value beyond is a ModelError, network.hpp;
// a fit's trial value beyond acts as the stop touching at rest).
inline double gap_center(double width, double center) { return std::clamp(center, -0.5 * width, 0.5 * width); }

// Polynomial spring: F = k1 e + k2 e^2 + k3 e^3, dF/de = k1 + 2 k2 e + 3 k3 e^2 (k1 > 0 [N/mm],
// k2 [N/mm^2], k3 [N/mm^3]). Not odd when k2 != 0: it stiffens on one side and softens on the
// other. Its tangent stays positive on the interval of `monotone_range` around e = 0.
struct PolyLaw {
  double k1, k2, k3;
  double force(double e) const { return e * (k1 + e * (k2 + k3 * e)); }
  double slope(double e) const { return k1 + e * (2.0 * k2 + 3.0 * k3 * e); }
  struct Range {
    double lo, hi;  // mm; infinite on a side where the tangent never reaches zero
  };
  // The roots of 3 k3 e^2 + 2 k2 e + k1 nearest e = 0 on each side (k1 > 0, so e = 0 is none).
  Range monotone_range() const {
    const double a = 3.0 * k3, b = 2.0 * k2, c = k1, inf = std::numeric_limits<double>::infinity();
    Range r{-inf, inf};
    auto take = [&](double root) {
      if (root > 0.0) r.hi = std::min(r.hi, root);
      else if (root < 0.0) r.lo = std::max(r.lo, root);
    };
    if (a == 0.0) {
      if (b != 0.0) take(-c / b);
    } else if (const double disc = b * b - 4.0 * a * c; disc >= 0.0) {
      const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));  // roots q/a and c/q
      take(q / a);
      if (q != 0.0) take(c / q);
    }
    return r;
  }
  static constexpr const char* monotone_advice = "bound k2 so that k2^2 < 3 k1 k3 with k3 > 0 (a law whose tangent stays positive)";
};

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
  // The smallest |e| [mm] at which the tangent reaches zero: the smallest positive root s = e^2
  // of 30 D30 s^2 + 12 D20 s + 2 D10 (D10 > 0); infinity when the law is monotone, which is
  // when D20 >= 0 and D30 >= 0, or D30 > 0 and D20^2 < (5/3) D10 D30.
  // What to tell a user whose Yeoh constants soften (every message about it ends with this).
  static constexpr const char* monotone_advice = "bound D20 so that D20^2 < (5/3) D10 D30 (a Yeoh law that stiffens again)";
  double softening_elongation() const {
    const double a = 30.0 * d30, b = 12.0 * d20, c = 2.0 * d10;
    double s = std::numeric_limits<double>::infinity();
    if (a == 0.0) {
      if (b < 0.0) s = -c / b;
    } else if (const double disc = b * b - 4.0 * a * c; disc >= 0.0) {
      const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));  // roots q/a and c/q
      for (double r : {q / a, q != 0.0 ? c / q : -1.0})
        if (r > 0.0) s = std::min(s, r);
    }
    return std::sqrt(s);
  }
};

}  // namespace rheo::runtime
