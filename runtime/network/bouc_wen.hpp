// Step relation of the Bouc-Wen smooth friction element (k [N/mm], n [-], fy [N]):
//   F = fy z,   dz/dt = (k/fy) de/dt (1 - |z|^n (1 + sgn(z de/dt)) / 2).
// The law is rate-independent. With s = k |de| / fy and w = sgn(de) z (z seen in the direction
// of the increment):
//   dw/ds = 1          for w < 0   (unloading towards z = 0: elastic, stiffness k),
//   dw/ds = 1 - w^n    for w >= 0  (loading: w -> 1 as s -> inf, never reached).
// A monotone increment de therefore maps z to that ODE's solution after s, which is the exact
// update for a piecewise-linear elongation history. The loading law is solved in closed form
// for n = 1, w = 1 - (1 - w0) e^-s; otherwise by its Taylor series in s to order 5, in substeps
// of at most ds_max = 0.1 / max(n, 2) (0.05 for n <= 2; the knee below w = 1 is ~1/n wide and
// the law decays there as e^{-n s}, so ds n <= 0.1 keeps the series accurate and far inside its
// stability limit, that of RK4 and beyond): global error O(ds^5), below 5e-9 in z per unit of s
// for n = 1.7 ... 4.5 at ds_max (RK4, before, 1e-8 to 9e-8), while a time step's s = k |de| / fy
// is usually below ds_max (one substep, local error O(s^6)). The coefficients are those of
// w' = f(w) = 1 - w^n, w'' = f' f, ..., in the derivatives of w^n up to the fourth, all from one
// power (w^(n-4) times powers of w for n >= 4; w^n divided by powers of w for non-integer
// n < 4, where w is kept away from 0; none for integer n <= 4): one power per substep and one
// for the slope, against four per substep and two more for RK4. For non-integer n < 4, w^n is
// not smooth at w = 0 and the steps there are graded.
// Slope (Newton): dF/dde = fy dz/dde = k dw/ds at the end of the increment.
// n -> inf gives friction(k, fy); bounds are +-fy, never reached.
//
// Termination (docs/numerics.md). With m = min(n, 1), 1 - w^n >= m (1 - w) on [0, 1], so
// 1 - w(s) <= (1 - w0) e^{-m s}: beyond s_sat = ln(2^53 (1 - w0)) / m + 1 the exact w is within
// an ulp of 1, and the march stops there (and wherever a substep no longer moves w). The
// substeps are therefore at most s_sat / ds_max plus the graded ones near w = 0 (w grows by a
// factor >= 1 + 0.05 m per step there), a bound computed once a march passes 16 substeps. The
// inverse (the increment that takes F_n to F) marches the same substeps as the forward relation
// until one would pass the target and solves that one substep's length (a root of the substep's
// polynomial) by a bracketed Newton iteration with bisection: no unbounded search, and
// step(inverse(F)) = F to rounding. A march or solve that exhausts its bound (never observed)
// returns NaN, which the tree solver turns into a NumericalError naming the element and the
// time.
#pragma once

#include "runtime/network/leaf_kernels.hpp"

#include <cmath>

namespace rheo::runtime {

struct BoucWenLaw {
  double k, n, fy;  // N/mm, -, N

  // dw/ds at w.
  double rate(double w) const { return w < 0.0 ? 1.0 : 1.0 - std::pow(w, n); }

  // Loading law from w >= 0 over s >= 0. NaN if the march exceeded its bound.
  double load(double w, double s) const { return march(w, s).force; }

  // z after a monotone increment de [mm] from z.
  double advance(double z, double de) const { return de == 0.0 ? z : monotone(z, de).force; }

  // Force at the end of the increment de from force F_n, and dF/dde.
  ForceSlope step(double force_before, double de) const {
    if (de == 0.0) return {force_before, k * rate(std::abs(force_before / fy))};
    const ForceSlope z = monotone(force_before / fy, de);
    return {fy * z.force, k * z.slope};
  }

  // Increment de that takes the force from F_n to F, and dde/dF; +-inf for |F| >= fy. A force
  // beyond what the discrete law reaches (within ~1e-16 fy of fy) maps to the increment where
  // the law saturates. NaN if a bound was exhausted.
  ForceSlope inverse(double force_before, double force) const;

 private:
  // {z, dw/ds at the end} after a monotone increment de != 0 from z (w = sgn(de) z).
  ForceSlope monotone(double z, double de) const {
    const double sign = de > 0.0 ? 1.0 : -1.0;
    double s = k * std::abs(de) / fy;
    double w = sign * z;
    if (w < 0.0) {
      if (s <= -w) return {sign * (w + s), 1.0};
      s += w;
      w = 0.0;
    }
    const ForceSlope end = march(w, s);
    return {sign * end.force, end.slope};
  }
  // {w, dw/ds} after the loading law from w >= 0 over s >= 0.
  ForceSlope march(double w, double s) const;
  // s with load(w0, s) = wt for 0 <= w0 < wt < 1 (the saturation length if wt is out of reach).
  double loading_length(double w0, double wt) const;
  // The loading law's Taylor series about w >= 0 (w > 0 for non-integer n < 4), to order 5:
  // w(s) = w + a1 s + ... + a5 s^5, a1 = dw/ds = 1 - w^n.
  struct Taylor {
    double w, a1, a2, a3, a4, a5;
    double at(double ds) const { return w + ds * (a1 + ds * (a2 + ds * (a3 + ds * (a4 + ds * a5)))); }
    double slope(double ds) const { return a1 + ds * (2.0 * a2 + ds * (3.0 * a3 + ds * (4.0 * a4 + ds * 5.0 * a5))); }
  };
  // w^n and g_k = w^(n-k), k = 1 ... 4 (d^k(w^n)/dw^k = n (n-1) ... (n-k+1) g_k; g_k = 0 where
  // that factor is, k > n for integer n): one power for any n (none for integer n <= 4).
  struct Powers {
    double p, g1, g2, g3, g4;
  };
  Powers powers(double w) const;
  Taylor taylor(double w, const Powers& g) const;
  // The series start for non-smooth n: w(s) = w0 + s - ((w0 + s)^(1+n) - w0^(1+n))/(1+n).
  double series(double w, double s) const { return w + s - (std::pow(w + s, 1.0 + n) - std::pow(w, 1.0 + n)) / (1.0 + n); }
  bool smooth() const { return n >= 4.0 || n == std::floor(n); }
  double ds_max() const { return 0.1 / (n > 2.0 ? n : 2.0); }
  double saturation_length(double w) const;  // s_sat above
  int max_substeps(double w) const;
};

}  // namespace rheo::runtime
