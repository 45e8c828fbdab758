// Root of a monotone non-decreasing scalar function by bracketing + safeguarded Newton.
//
// Contract: f(x) returns {value, slope} with value non-decreasing in x and slope >= 0 its
// derivative (0 allowed on flat pieces). Starting from x0, the root is bracketed within
// [domain_lo, domain_hi] (either may be infinite; a finite end must have been checked by the
// caller to hold a sign change) and refined until |value| <= value_tolerance or the bracket is
// below 1e-15 relative. With `leftmost`, the invariant f(a) < 0 <= f(b) converges to the left
// end of a flat zero set; otherwise f(a) <= 0 < f(b) converges to its right end.
// Exact in one Newton step for linear f. No allocation.
//
// Bounded: at most kBracketSteps doublings to bracket the root and `refine_steps` refinements,
// of which every third that has not halved the bracket is a bisection. Returns NaN when a bound
// is exhausted (no sign change found, or the bracket not resolved): the caller turns that into a
// NumericalError naming the element and the time, never a hang or a silent value.
#pragma once

#include "runtime/network/leaf_kernels.hpp"

#include <cmath>
#include <limits>

namespace rheo::runtime {

inline constexpr int kBracketSteps = 1100;  // doublings: from any step to beyond double range
inline constexpr int kRefineSteps = 400;

template <class F>
double solve_monotone(F&& f, double x0, double step_hint, double domain_lo, double domain_hi, double value_tolerance, bool leftmost = true,
                      int refine_steps = kRefineSteps) {
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
      if (!below(fb) || b >= domain_hi) break;
      if (i >= kBracketSteps) return std::numeric_limits<double>::quiet_NaN();
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
      if (below(fa) || a <= domain_lo) break;
      if (i >= kBracketSteps) return std::numeric_limits<double>::quiet_NaN();
      if (std::abs(fa) <= value_tolerance) return a;
      b = a, fb = fa;
      step *= 2.0;
    }
  }
  if (std::abs(fb) <= value_tolerance) return b;  // the bracketing landed on the root
  if (std::abs(fa) <= value_tolerance) return a;
  // Newton from the end nearer the root, bisection when Newton leaves the bracket.
  double x = std::abs(fa) < std::abs(fb) ? a : b;
  ForceSlope fx{std::abs(fa) < std::abs(fb) ? fa : fb, 0.0};
  fx = f(x);
  double width = b - a;
  for (int iteration = 0; iteration < refine_steps; ++iteration) {
    double next = fx.slope > 0.0 ? x - fx.force / fx.slope : std::numeric_limits<double>::quiet_NaN();
    if (!(next > a && next < b) || (iteration % 3 == 2 && b - a > 0.5 * width)) next = 0.5 * (a + b);
    if (iteration % 3 == 2) width = b - a;
    x = next;
    fx = f(x);
    if (std::abs(fx.force) <= value_tolerance) return x;
    if (below(fx.force)) a = x;
    else b = x;
    if (b - a <= 1e-15 * (std::abs(a) + std::abs(b)) + std::numeric_limits<double>::min()) return leftmost ? b : a;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace rheo::runtime
