// Step relation of the Bouc-Wen smooth friction element (k [N/mm], n [-], fy [N]):
//   F = fy z,   dz/dt = (k/fy) de/dt (1 - |z|^n (1 + sgn(z de/dt)) / 2).
// The law is rate-independent. With s = k |de| / fy and w = sgn(de) z (z seen in the direction
// of the increment):
//   dw/ds = 1          for w < 0   (unloading towards z = 0: elastic, stiffness k),
//   dw/ds = 1 - w^n    for w >= 0  (loading: w -> 1 as s -> inf, never reached).
// A monotone increment de therefore maps z to that ODE's solution after s, which is the exact
// update for a piecewise-linear elongation history. The loading law is solved in closed form
// for n = 1, w = 1 - (1 - w0) e^-s; otherwise by RK4 in s with steps of at most
// ds_max = 0.1 / max(n, 2) (0.05 for n <= 2; the knee below w = 1 is ~1/n wide and the law
// decays there as e^{-n s}, so ds n <= 0.1 keeps RK4 accurate and far inside its stability
// limit 2.78): global error O(ds^4), about 1e-8 in z per unit of s for n = 2 at ds = 0.05,
// while a time step's s = k |de| / fy is usually below ds_max (one substep, local error
// O(s^5)). For non-integer n < 4, w^n is not smooth at w = 0 and the steps there are graded.
// Slope (Newton): dF/dde = fy dz/dde = k dw/ds at the end of the increment.
// n -> inf gives friction(k, fy); bounds are +-fy, never reached.
#pragma once

#include "runtime/network/leaf_kernels.hpp"
#include "runtime/network/monotone_solve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rheo::runtime {

struct BoucWenLaw {
  double k, n, fy;  // N/mm, -, N

  // dw/ds at w.
  double rate(double w) const { return w < 0.0 ? 1.0 : 1.0 - std::pow(w, n); }

  // Loading law from w >= 0 over s >= 0.
  double load(double w, double s) const {
    if (n == 1.0) return w - (1.0 - w) * std::expm1(-s);
    const double ds_max = 0.1 / std::max(n, 2.0);
    auto rk4 = [&](double ds) {
      const double k1 = rate(w), k2 = rate(w + 0.5 * ds * k1), k3 = rate(w + 0.5 * ds * k2), k4 = rate(w + ds * k3);
      w += ds / 6.0 * (k1 + 2.0 * (k2 + k3) + k4);
    };
    // Within 1e-16 of the asymptote w = 1 (1 - w ~ rate/n): nothing left to integrate.
    auto saturated = [&] { return rate(w) <= 1e-16; };
    if (n >= 4.0 || n == std::floor(n)) {  // w^n smooth: steps of ds_max and a remainder (continuous in s)
      for (; s > 0.0 && !saturated(); s -= std::min(s, ds_max)) rk4(std::min(s, ds_max));
      return w;
    }
    // w^n singular at w = 0 in a derivative RK4 needs: steps of at most w/10 there (local
    // error ~1e-8 w^(1+n)), after a first stretch of s <= 1e-6 from the series
    // w(s) = w0 + s - ((w0 + s)^(1+n) - w0^(1+n))/(1+n) + O(s^(1+2n)).
    if (w < 1e-6) {
      const double s1 = std::min(s, 1e-6);
      w += s1 - (std::pow(w + s1, 1.0 + n) - std::pow(w, 1.0 + n)) / (1.0 + n);
      s -= s1;
    }
    while (s > 0.0 && !saturated()) {
      const double ds = std::min({s, ds_max, 0.1 * w});
      rk4(ds);
      s -= ds;
    }
    return w;
  }

  // z after a monotone increment de [mm] from z.
  double advance(double z, double de) const {
    if (de == 0.0) return z;
    const double sign = de > 0.0 ? 1.0 : -1.0;
    double s = k * std::abs(de) / fy;
    double w = sign * z;
    if (w < 0.0) {
      if (s <= -w) return sign * (w + s);
      s += w;
      w = 0.0;
    }
    return sign * load(w, s);
  }

  // Force at the end of the increment de from force F_n, and dF/dde.
  ForceSlope step(double force_before, double de) const {
    if (de == 0.0) return {force_before, k * rate(std::abs(force_before / fy))};
    const double z = advance(force_before / fy, de);
    return {fy * z, k * rate(de > 0.0 ? z : -z)};
  }

  // Increment de that takes the force from F_n to F, and dde/dF; +-inf for |F| >= fy.
  ForceSlope inverse(double force_before, double force) const {
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
    if (n == 1.0) {
      s += std::log1p((wt - w0) / (1.0 - wt));
    } else {
      auto residual = [&](double x) {
        const double w = load(w0, x);
        return ForceSlope{w - wt, rate(w)};
      };
      s += solve_monotone(residual, wt - w0, wt - w0, 0.0, inf, 1e-15);
    }
    return {sign * s * fy / k, 1.0 / (k * rate(wt))};
  }
};

}  // namespace rheo::runtime
