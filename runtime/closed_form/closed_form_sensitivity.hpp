// Derivatives of a closed-form harmonic point (periodic_closed_form.hpp) with respect to the
// network's root coefficients, for networks whose every element sits in the root parallel
// block (the thesis models, Figs. 2.5, 5.1, 5.3; springpots, whose Maxwell modes are root
// coefficients too) and a drive without preload.
//
// The coefficients, flattened (coefficient_vector), are
//   spring_k, dashpot_c, then per yeoh D10, D20, D30, per Maxwell element k, c, per friction
//   element k, fy, per slider fy                                         [N/mm^n, N s/mm, N].
// Each harmonic point is summarised by F^ [N] and the first harmonic K'_1, K''_1 [N/mm], from
// which measures_from (cycle_measures.hpp) makes K and the phase by either definition. K'_1 and
// K''_1 are sums over branches (periodic_closed_form.hpp); their derivatives are those of each
// branch's term:
//   spring k       dK' = 1
//   dashpot c      dK'' = w
//   yeoh           dK'/dD10 = 2, dK'/dD20 = 3 u0^2, dK'/dD30 = (15/4) u0^4
//   Maxwell k, c   x = w c / k:  dK'/dk = x^2 (x^2 - 1) / (1 + x^2)^2, dK''/dk = 2 x^3 / (1 + x^2)^2,
//                  dK'/dc = 2 w x / (1 + x^2)^2,  dK''/dc = w (1 - x^2) / (1 + x^2)^2   (from B.58)
//   friction k, fy (u0 > uy = fy/k; else as a spring k): s = 2 uy/u0 - 1,
//                  K' = (k/pi) g(s), g(s) = asin s + pi/2 + s sqrt(1 - s^2), g'(s) = 2 sqrt(1 - s^2);
//                  dK'/dk = g/pi - (k/pi) g' 2 fy / (k^2 u0),  dK'/dfy = 2 g' / (pi u0),
//                  K'' = 4 fy (u0 - uy) / (pi u0^2):  dK''/dk = 4 fy^2 / (pi k^2 u0^2),
//                  dK''/dfy = 4 (u0 - 2 uy) / (pi u0^2)                                (C.2)
//   slider fy      dK'' = 4 / (pi u0)
// F^ = max over theta of the loading half's force F(theta; C). By the envelope theorem (the
// maximum is at a stationary point or at a fixed end of [-pi/2, pi/2]) dF^/dC = dF/dC at the
// peak phase theta*, with u = u0 sin theta*, c = cos theta*:
//   spring u;  dashpot w u0 c;  yeoh 2 u, 4 u^3, 6 u^5;  Maxwell u0 (dK'/d. sin + dK''/d. cos);
//   friction (u0 > uy: the loop branch min(fy, -fy + k u0 (1 + sin theta))): before its slip
//   phase dF/dk = u0 (1 + sin theta*), dF/dfy = -1; slipping dF/dk = 0, dF/dfy = 1; u0 <= uy
//   (never slips) dF/dk = u;   slider 1.
// Where the peak lies exactly at a friction element's slip phase F^ has a kink in C; either
// one-sided derivative is returned.
#pragma once

#include "runtime/core/harmonic_point.hpp"
#include "runtime/network/network.hpp"

#include <optional>
#include <vector>

namespace rheo::runtime {

// The root coefficients in the order above.
std::vector<double> coefficient_vector(const Coefficients& c);

// True when every element sits in the root parallel block (no subtree of any kind), so that a
// harmonic point is a function of the root coefficients alone.
bool has_coefficient_sensitivities(const Network& network);

struct HarmonicSensitivity {
  HarmonicPoint point;  // as closed_form_harmonic_point gives it
  // d/dC_k of F^, K'_1, K''_1, k over coefficient_vector.
  std::vector<double> force_amplitude, storage, loss;
};

// Requires has_coefficient_sensitivities(network), amplitude > 0 [mm], frequency > 0 [Hz]. The
// point at preload 0 and its derivatives.
HarmonicSensitivity harmonic_sensitivity(const Network& network, double amplitude, double frequency, HarmonicDefinition definition);

// The derivatives of the measures the fit compares (objective.hpp), K [N/mm] and the phase's
// sine and cosine, given those of F^, K'_1 and K''_1 (any one direction), by the definition the
// point was made with: thesis K = F^/u0, sin = d = u0 K''_1 / F^ (0 where d > 1 is clamped),
// cos = sign(K'_1) sqrt(1 - d^2); first harmonic K = |K*_1|, sin = K''_1 / K, cos = K'_1 / K.
struct MeasureDerivative {
  double stiffness = 0.0, sine = 0.0, cosine = 0.0;
};
MeasureDerivative measure_derivative(const HarmonicSensitivity& s, HarmonicDefinition definition, double d_force_amplitude, double d_storage,
                                     double d_loss);

}  // namespace rheo::runtime
