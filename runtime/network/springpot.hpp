// The springpot (fractional derivative element, Kari & Sjoberg) and its Maxwell-chain
// approximation.
//
// Springpot k [N/mm], alpha [-] (0 < alpha < 1), tau [s]:
//   F = k tau^alpha d^alpha e / dt^alpha,        K*(w) = k (i w tau)^alpha,
// so |K*| = k (w tau)^alpha and the phase is alpha * 90 deg at every frequency: alpha -> 0 is
// a spring k, alpha -> 1 a dashpot k tau. Relaxation modulus G(t) = k (t/tau)^-alpha / Gamma(1 - alpha).
//
// Its relaxation spectrum over relaxation times l [s] (G(t) = int H(l) e^{-t/l} d ln l) is
//   H(l) = A l^-alpha,   A = k tau^alpha sin(alpha pi) / pi.
// rheo discretises it into Maxwell elements (k_j, c_j = k_j l_j), which every integrator
// handles exactly:
//   - the band [f_low, f_high] of the element is widened by kMarginDecades on each side:
//     l_lo = 1 / (2 pi f_high) / 10^m, l_hi = 1 / (2 pi f_low) * 10^m;
//   - n = ceil(kModesPerDecade * log10(l_hi / l_lo)) interior modes at the log-midpoints
//     l_j = l_lo e^{(j + 1/2) h}, h = ln(l_hi / l_lo) / n, with k_j = H(l_j) h (the midpoint
//     rule in ln l, whose error falls like e^{-pi^2 / h} since the Maxwell kernel
//     i w l / (1 + i w l) is analytic in a strip of half-width pi/2 around the real ln l axis);
//   - the slow tail l > l_hi as one Maxwell element with the tail's stiffness and first inverse
//     moment: k_s = int H = A l_hi^-alpha / alpha, l_s = l_hi (1 + alpha) / alpha;
//   - the fast tail l < l_lo as one Maxwell element with the tail's damping and its second
//     moment: c_f = int H l = A l_lo^(1 - alpha) / (1 - alpha), l_f = l_lo (1 - alpha) / (2 - alpha).
// The chain has no static stiffness (the springpot relaxes completely) and a finite
// instantaneous stiffness sum k_j. Within [f_low, f_high], for 0.02 <= alpha <= 0.98, |K*| is
// within 5e-4 (relative) and the phase within 0.02 deg of k (i w tau)^alpha
// (tests/runtime/network/springpot_test.cpp). Outside the band it departs: below f_low it tends to the
// slow tail's stiffness-less relaxation, above f_high to the chain's instantaneous stiffness.
#pragma once

#include <span>

namespace rheo::runtime {

inline constexpr double kSpringpotModesPerDecade = 4.0;
inline constexpr double kSpringpotMarginDecades = 1.5;

struct SpringpotParameters {
  double k, alpha, tau;  // N/mm, -, s
  double f_low, f_high;  // Hz, the band where the approximation holds
};

// Number of Maxwell elements of the chain for a band (interior modes + the two tails).
// Requires 0 < f_low < f_high.
int springpot_mode_count(double f_low, double f_high);

// Writes the chain's Maxwell stiffnesses k_j [N/mm] and dampings c_j [N*s/mm]; both spans have
// springpot_mode_count(p.f_low, p.f_high) entries (a chain compiled for one band keeps its mode
// count when fitting changes the parameters: the modes are spread over the new band).
void springpot_modes(const SpringpotParameters& p, std::span<double> stiffness, std::span<double> damping);

}  // namespace rheo::runtime
