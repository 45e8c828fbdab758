#include "runtime/network/bouc_wen.hpp"

#include <algorithm>
#include <limits>

namespace rheo::runtime {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kSeriesStretch = 1e-6;  // s of the series start near w = 0 (non-smooth n)
constexpr double kSaturated = 1e-16;     // dw/ds below which nothing is left to integrate
constexpr int kFreeSubsteps = 16;        // substeps every bound allows (max_substeps adds 16)

// x in (0, length] with g(x) = 0 for g increasing, g(0) < 0 <= g(length), where `g(x)` gives
// {g, dg/dx}: Newton from x0, with a bisection whenever a step leaves the bracket or three steps
// have not halved it. Ends when a Newton step is within rounding of x or the bracket is within
// rounding of its end; at most 200 iterations (bisection alone resolves any bracket in 64).
template <class G>
double solve_bracketed(G&& g, double length, double x0) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  double a = 0.0, b = length, x = x0 > 0.0 && x0 < length ? x0 : length;
  double width = b - a;
  for (int i = 0; i < 200; ++i) {
    const ForceSlope v = g(x);
    if (v.force == 0.0) return x;
    (v.force < 0.0 ? a : b) = x;
    if (b - a <= 4.0 * eps * b) return b;
    double next = v.slope > 0.0 ? x - v.force / v.slope : kNaN;
    if (next > a && next < b && std::abs(next - x) <= 2.0 * eps * x) return next;
    if (!(next > a && next < b) || (i % 3 == 2 && b - a > 0.5 * width)) next = 0.5 * (a + b);
    if (i % 3 == 2) width = b - a;
    x = next;
  }
  return kNaN;
}
}  // namespace

BoucWenLaw::Powers BoucWenLaw::powers(double w) const {
  if (n == std::floor(n) && n <= 4.0) {
    const double w2 = w * w;
    const double pw[5] = {1.0, w, w2, w2 * w, w2 * w2};
    const auto at = [&](double e) { return e >= 0.0 ? pw[static_cast<int>(e)] : 0.0; };  // its factor is 0 for k > n
    return {at(n), at(n - 1.0), at(n - 2.0), at(n - 3.0), at(n - 4.0)};
  }
  if (n >= 4.0) {
    const double g4 = std::pow(w, n - 4.0), g3 = g4 * w, g2 = g3 * w, g1 = g2 * w;
    return {g1 * w, g1, g2, g3, g4};
  }
  const double p = std::pow(w, n), inverse = 1.0 / w;  // w > 0 (graded)
  const double g1 = p * inverse, g2 = g1 * inverse, g3 = g2 * inverse;
  return {p, g1, g2, g3, g3 * inverse};
}

BoucWenLaw::Taylor BoucWenLaw::taylor(double w, const Powers& g) const {
  // f = dw/ds = 1 - w^n and its derivatives f1 ... f4 in w. The coefficients are d^k w/ds^k / k!:
  //   w1 = f, w2 = f1 f, w3 = (f2 f + f1^2) f, w4 = (f3 f^2 + 4 f2 f1 f + f1^3) f,
  //   w5 = (f4 f^3 + 7 f3 f1 f^2 + 4 f2^2 f^2 + 11 f2 f1^2 f + f1^4) f.
  const double f = 1.0 - g.p, c1 = -n, c2 = c1 * (n - 1.0), c3 = c2 * (n - 2.0), c4 = c3 * (n - 3.0);
  const double f1 = c1 * g.g1, f2 = c2 * g.g2, f3 = c3 * g.g3, f4 = c4 * g.g4, f1f1 = f1 * f1;
  return {w,
          f,
          0.5 * f1 * f,
          (1.0 / 6.0) * (f2 * f + f1f1) * f,
          (1.0 / 24.0) * ((f3 * f + 4.0 * f2 * f1) * f + f1f1 * f1) * f,
          (1.0 / 120.0) * ((((f4 * f + 7.0 * f3 * f1 + 4.0 * f2 * f2) * f + 11.0 * f2 * f1f1) * f + f1f1 * f1f1) * f)};
}

double BoucWenLaw::saturation_length(double w) const {
  const double m = std::min(n, 1.0);
  return std::log(std::max(1.0 - w, 0x1p-53) * 0x1p53) / m + 1.0;
}

int BoucWenLaw::max_substeps(double w) const {
  const double m = std::min(n, 1.0);
  const double bound = saturation_length(w) / ds_max() + (smooth() ? 0.0 : std::log(1.0 / kSeriesStretch) / std::log1p(0.05 * m)) + kFreeSubsteps;
  return static_cast<int>(std::min(bound, 1e9));
}

ForceSlope BoucWenLaw::march(double w, double s) const {
  if (n == 1.0) {
    const double end = w - (1.0 - w) * std::expm1(-s);
    return {end, rate(end)};
  }
  if (s > 1.0) s = std::min(s, saturation_length(w));  // beyond it w is 1 to the last ulp (s_sat >= 1)
  const double full = ds_max();
  const bool graded = !smooth();
  if (graded && w < kSeriesStretch) {  // w^n singular at w = 0 in the series' derivatives
    const double s1 = std::min(s, kSeriesStretch);
    w = series(w, s1);
    s -= s1;
  }
  // The bound on substeps (max_substeps, two logarithms) is at least kFreeSubsteps: taken only
  // by a march that gets that far.
  const double from = w;
  int cap = 0;
  Powers g = powers(w);
  for (int i = 0; s > 0.0 && 1.0 - g.p > kSaturated; ++i) {
    if (i >= kFreeSubsteps) {
      if (cap == 0) cap = max_substeps(from);
      if (i == cap) return {kNaN, kNaN};
    }
    const double ds = graded ? std::min({s, full, 0.1 * w}) : std::min(s, full);
    const double next = taylor(w, g).at(ds);
    if (!(next > w)) break;  // no longer moves in double precision: saturated
    w = next;
    s -= ds;
    g = powers(w);
  }
  return {w, 1.0 - g.p};
}

double BoucWenLaw::loading_length(double w0, double wt) const {
  if (n == 1.0) return std::log1p((wt - w0) / (1.0 - wt));
  // The first guess of a substep's length: the rate at its start.
  auto guess = [&](double from) { return (wt - from) / rate(from); };
  double s = 0.0, w = w0;
  if (!smooth() && w < kSeriesStretch) {
    if (series(w0, kSeriesStretch) >= wt)
      return solve_bracketed(
          [&](double x) {
            const double v = series(w0, x);
            return ForceSlope{v - wt, rate(v)};
          },
          kSeriesStretch, guess(w0));
    w = series(w0, kSeriesStretch);
    s = kSeriesStretch;
  }
  const double start = w;
  int cap = 0;
  Powers g = powers(w);
  for (int i = 0; 1.0 - g.p > kSaturated; ++i) {
    if (i >= kFreeSubsteps) {  // as in march()
      if (cap == 0) cap = max_substeps(start);
      if (i == cap) return kNaN;
    }
    const double ds = smooth() ? ds_max() : std::min(ds_max(), 0.1 * w);
    const Taylor t = taylor(w, g);
    const double next = t.at(ds);
    if (next >= wt) return s + solve_bracketed([&](double x) { return ForceSlope{t.at(x) - wt, t.slope(x)}; }, ds, (wt - w) / t.a1);
    if (!(next > w)) break;
    w = next;
    s += ds;
    g = powers(w);
  }
  return s;  // wt is out of the discrete law's reach: where it saturates
}

ForceSlope BoucWenLaw::inverse(double force_before, double force) const {
  constexpr double inf = std::numeric_limits<double>::infinity();
  if (force >= fy) return {inf, inf};
  if (force <= -fy) return {-inf, inf};
  if (force == force_before) return {0.0, 1.0 / (k * rate(std::abs(force / fy)))};
  const double sign = force > force_before ? 1.0 : -1.0;
  double w0 = sign * force_before / fy;
  const double wt = sign * force / fy;
  double s = 0.0;
  if (w0 < 0.0) {
    if (wt <= 0.0) return {sign * (wt - w0) * fy / k, 1.0 / k};
    s = -w0;
    w0 = 0.0;
  }
  s += loading_length(w0, wt);
  return {sign * s * fy / k, 1.0 / (k * rate(wt))};
}

}  // namespace rheo::runtime
