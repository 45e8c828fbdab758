// The dissertation's analytical approximation of the harmonic response (section 5.2.2) and its
// calibration against the time-stepped response (section 5.2.1, Table 5.1).
//
// Structure (Figs. 5.1, 5.3): springs, yeoh springs, Maxwell elements and friction elements,
// all in the root parallel block. Per point (u0 [mm], f [Hz]), w = 2 pi f:
//   K_e = sum k_spring + sum 2 D10                         [N/mm]  (5.34, 5.35: a yeoh spring
//                                                                   counts with its small-
//                                                                   displacement stiffness)
//   Maxwell j (K_v, t_r = c/K_v), x = w t_r:
//     K_dyn^{v,j} = |K*_j| = K_v x / sqrt(1 + x^2)          [N/mm]  (5.11; see below on 5.12)
//     d_v^j = sin(delta_v^j) = 1 / sqrt(1 + x^2)                    (5.13)
//   K_dyn^v = sqrt((K_e + sum K^{v,j} cos delta_v^j)^2 + (sum K^{v,j} sin delta_v^j)^2)  (5.14)
//   d_v = (1 / K_dyn^v) sum K^{v,j} sin delta_v^j                   (5.15)
//   friction q (K_p, u_s = fy/K_p):
//     K_dyn^{p,q} = K_p u_s / u0 if u_s < u0, else K_p      [N/mm]  (5.16)
//     U_s^q = 4 K_p u_s (u0 - u_s) if u_s < u0, else 0      [N mm]  (5.17)
//   K_dyn^p = sum K_dyn^{p,q}                                        (5.18)
//   d_p = sum U_s^q / (pi u0 F^_p),  F^_p = u0 K_dyn^p = sum min(K_p u0, K_p u_s)  [N]  (5.19)
//   K_dyn = K_dyn^v + K_dyn^p                                        (5.20)
//   d = sin(delta) = (K_dyn^v d_v + K_dyn^p d_p) / K_dyn             (5.21)
// Reported: stiffness K_dyn, damping d, phase asin(min(d, 1)), storage/loss K cos/sin(phase),
// F^ = K u0, U = pi F^ u0 d (the thesis definition of d read backwards).
//
// Eq. 5.12 as printed, K_v x^2 / (1 + x^2), is Re K*_j (the storage stiffness), not |K*_j|,
// although the text states K_dyn^{v,j} = |K*_j| with (5.11), and (5.13) is sin(arg K*_j). Only
// |K*_j| = K_v x / sqrt(1 + x^2) makes (5.14) the modulus of K_e + sum K*_j (the vector sum of
// Fig. 5.2: K^{v,j} cos delta = Re, K^{v,j} sin delta = Im) and (5.15) sin(arg) of it; with the
// printed form the two would count the storage factor x / sqrt(1 + x^2) twice. So |K*_j| it is,
// and for a linear network (no friction) the approximation is exact: K_dyn = |K*|, d = sin arg K*.
//
// Eq. 5.19 as printed divides by pi u0 sum K_p u_s, which is the frictional force amplitude F^_p
// only when every element slips (C.19 is derived for that case). An element that does not slip
// carries K_p u0 < K_p u_s at the turning point, so the printed form underestimates d_p as soon
// as some elements slip and others do not. We use F^_p = u0 K_dyn^p (5.18), the same amplitude
// the stiffness uses; it equals the printed denominator when all slip, and it makes the
// approximation exact for springs + friction elements (C.15, C.17-C.18 with d = U/(pi F^ u0),
// C.12), where all branch forces peak together at u = u0.
//
// Calibration (Table 5.1): corr_K = K_num / K_approx (5.2), corr_d = d_num / d_approx (5.3), and
// the calibrated response K_approx corr_K, d_approx corr_d enters phi_corr (5.4).
#pragma once

#include "runtime/protocols/harmonic.hpp"
#include "runtime/network/network.hpp"

#include <string>
#include <vector>

namespace rheo::runtime {

// Why NETWORK does not have the structure above, naming the first element (source order) that
// does not fit it (a dashpot, a slider or any element inside a nested block; a series spring +
// dashpot pair is a Maxwell element and fits) and saying to use method = exact; empty when it
// has. fit() reports it as the UsageError of a fit by the approximate or corrected method.
std::string approximation_misfit(const Network& network);

// One point per (amplitudes[i], frequencies[i]) pair (same length; pointwise, not a grid), in
// that order; converged = true, cycles = 0. Preconditions (std::logic_error otherwise): an
// empty approximation_misfit, equal lengths, positive amplitudes and frequencies. The points
// are evaluated THREADS at a time (parallel_for.hpp), the same points for every value.
std::vector<HarmonicPoint> approximate_harmonic(const Network& network, const std::vector<double>& amplitudes,
                                                const std::vector<double>& frequencies, int threads = 1);

// Correction factors of Table 5.1, one per point. `approximate` and `numerical` must hold the
// same points (amplitude and frequency equal to 1e-12 relative) in the same order, else
// std::logic_error. Where d_approx = 0 (no Maxwell element, no slipping friction element:
// then d_num = 0 too) eq. 5.3 is undefined and corr_d = 1.
struct ThesisCorrection {
  std::vector<double> stiffness;  // corr_K (5.2)
  std::vector<double> damping;    // corr_d (5.3)
};
ThesisCorrection thesis_correction(const std::vector<HarmonicPoint>& approximate, const std::vector<HarmonicPoint>& numerical);

// In place (5.4): K *= corr_K, d *= corr_d, phase = asin(min(d, 1)); storage, loss, F^ and U
// follow. Throws std::logic_error when the sizes differ.
void apply_correction(const ThesisCorrection& correction, std::vector<HarmonicPoint>& approximate);

}  // namespace rheo::runtime
