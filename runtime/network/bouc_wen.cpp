#include "runtime/network/bouc_wen.hpp"

#include <algorithm>
#include <limits>

namespace rheo::runtime {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kSeriesStretch = 1e-6;  // s of the series start near w = 0 (non-smooth n)
constexpr double kSaturated = 1e-16;     // dw/ds below which nothing is left to integrate

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

double BoucWenLaw::rk4(double w, double ds) const {
  const double k1 = rate(w), k2 = rate(w + 0.5 * ds * k1), k3 = rate(w + 0.5 * ds * k2), k4 = rate(w + ds * k3);
  return w + ds / 6.0 * (k1 + 2.0 * (k2 + k3) + k4);
}

double BoucWenLaw::saturation_length(double w) const {
  const double m = std::min(n, 1.0);
  return std::log(std::max(1.0 - w, 0x1p-53) * 0x1p53) / m + 1.0;
}

int BoucWenLaw::max_substeps(double w) const {
  const double m = std::min(n, 1.0);
  const double bound = saturation_length(w) / ds_max() + (smooth() ? 0.0 : std::log(1.0 / kSeriesStretch) / std::log1p(0.05 * m)) + 16.0;
  return static_cast<int>(std::min(bound, 1e9));
}

double BoucWenLaw::load(double w, double s) const {
  if (n == 1.0) return w - (1.0 - w) * std::expm1(-s);
  s = std::min(s, saturation_length(w));  // beyond it w is 1 to the last ulp
  const double full = ds_max();
  if (!smooth() && w < kSeriesStretch) {  // w^n singular at w = 0 in a derivative RK4 needs
    const double s1 = std::min(s, kSeriesStretch);
    w = series(w, s1);
    s -= s1;
  }
  const int cap = max_substeps(w);
  for (int i = 0; s > 0.0 && rate(w) > kSaturated; ++i) {
    if (i == cap) return kNaN;
    const double ds = smooth() ? std::min(s, full) : std::min({s, full, 0.1 * w});
    const double next = rk4(w, ds);
    if (!(next > w)) break;  // no longer moves in double precision: saturated
    w = next;
    s -= ds;
  }
  return w;
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
  const int cap = max_substeps(w);
  for (int i = 0; rate(w) > kSaturated; ++i) {
    if (i == cap) return kNaN;
    const double ds = smooth() ? ds_max() : std::min(ds_max(), 0.1 * w);
    const double next = rk4(w, ds);
    if (next >= wt) {
      const double from = w;
      return s + solve_bracketed(
                     [&](double x) {
                       const double v = rk4(from, x);
                       return ForceSlope{v - wt, rate(v)};
                     },
                     ds, guess(from));
    }
    if (!(next > w)) break;
    w = next;
    s += ds;
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
