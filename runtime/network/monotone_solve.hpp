// Root of a monotone non-decreasing scalar function by bracketing + safeguarded Newton.
//
// Contract: f(x) returns {value, slope} with value non-decreasing in x and slope >= 0 its
// derivative (0 allowed on flat pieces). Starting from x0, the root is bracketed within
// [domain_lo, domain_hi] (either may be infinite; a finite end must have been checked by the
// caller to hold a sign change) and refined until |value| <= value_tolerance or the bracket is
// below 1e-15 relative. With `leftmost`, the invariant f(a) < 0 <= f(b) converges to the left
// end of a flat zero set; otherwise f(a) <= 0 < f(b) converges to its right end.
// Exact in one Newton step for linear f. No allocation.
#pragma once

#include "runtime/network/leaf_kernels.hpp"

#include <cmath>
#include <limits>

namespace rheo::runtime {

template <class F>
double solve_monotone(F&& f, double x0, double step_hint, double domain_lo, double domain_hi, double value_tolerance, bool leftmost = true) {
  auto below = [&](double v) { return leftmost ? v < 0.0 : v <= 0.0; };
  ForceSlope at = f(x0);
  if (std::abs(at.force) <= value_tolerance) return x0;
  double a, b, fa, fb;
  double step = at.slope > 0.0 ? std::abs(at.force) / at.slope : std::abs(step_hint);
  if (!(step > 0.0) || !std::isfinite(step)) step = std::abs(step_hint) > 0.0 ? std::abs(step_hint) : 1.0;
  if (below(at.force)) {
    a = x0, fa = at.force;
    for (int i = 0;; ++i) {
      b = std::isfinite(domain_hi) ? std::min(a + step, domain_hi) : a + step;
      ForceSlope fb_ = f(b);
      fb = fb_.force;
      if (!below(fb) || b >= domain_hi || i > 1100) break;
      if (std::abs(fb) <= value_tolerance) return b;
      a = b, fa = fb;
      step *= 2.0;
    }
  } else {
    b = x0, fb = at.force;
    for (int i = 0;; ++i) {
      a = std::isfinite(domain_lo) ? std::max(b - step, domain_lo) : b - step;
      ForceSlope fa_ = f(a);
      fa = fa_.force;
      if (below(fa) || a <= domain_lo || i > 1100) break;
      if (std::abs(fa) <= value_tolerance) return a;
      b = a, fb = fa;
      step *= 2.0;
    }
  }
  // Newton from the end nearer the root, bisection when Newton leaves the bracket.
  double x = std::abs(fa) < std::abs(fb) ? a : b;
  ForceSlope fx{std::abs(fa) < std::abs(fb) ? fa : fb, 0.0};
  fx = f(x);
  for (int iteration = 0; iteration < 200; ++iteration) {
    double next = fx.slope > 0.0 ? x - fx.force / fx.slope : std::numeric_limits<double>::quiet_NaN();
    if (!(next > a && next < b)) next = 0.5 * (a + b);
    x = next;
    fx = f(x);
    if (std::abs(fx.force) <= value_tolerance) return x;
    if (below(fx.force)) a = x;
    else b = x;
    if (b - a <= 1e-15 * (std::abs(a) + std::abs(b)) + std::numeric_limits<double>::min()) break;
  }
  return leftmost ? b : a;
}

}  // namespace rheo::runtime
