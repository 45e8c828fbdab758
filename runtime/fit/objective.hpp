// The dissertation's error measures between a model's harmonic response and measured data.
//
//   phi = sum_i [ w_K (K_th,i / K_exp,i - 1)^2 + w_d (d_th,i / d_exp,i - 1)^2 ]
// with d = sin(phase): eq. 5.1 for w_K = w_d = 1, eq. 5.38 for w_K = k, w_d = 1 - k.
//   err = sqrt(phi_5.1) / n                                                  (eq. 6.1)
#pragma once

#include "runtime/protocols/harmonic.hpp"
#include "runtime/io/harmonic_data.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace rheo::runtime {

// Eq. 5.1's relative damping error sin(phase_model) / sin(phase_measured) - 1 [-]; 0 (the term
// left out) where the measured phase [rad] is <= 0 or >= pi, which noise on a nearly elastic (or
// nearly undamped mass-dominated) point can give (it has no relative error: the quotient changes
// sign or is infinite).
double damping_residual(double model_phase, double measured_phase);
// Whether eq. 5.1 keeps a point's damping term: its measured phase [rad] in (0, pi).
inline bool keeps_damping_term(double measured_phase) { return measured_phase > 0.0 && measured_phase < std::numbers::pi; }

// Eq. 5.1's relative stiffness error K_th / K_exp - 1 [-], each stiffness [N/mm] signed by its
// storage part: a point above a resonance (phase [rad] beyond pi/2, where the thesis definition
// writes 180 deg - asin d) counts as -K. Below every resonance this is eq. 5.1 unchanged; a model
// on the other side of a resonance than the data scores <= -1, not a match.
double stiffness_residual(double model_stiffness, double model_phase, double measured_stiffness, double measured_phase);
// A stiffness [N/mm] signed by its storage part, -K where cos(phase) < 0, as stiffness_residual signs both.
inline double signed_stiffness(double stiffness, double phase) { return std::cos(phase) < 0.0 ? -stiffness : stiffness; }

// "FILE:ROW: phase ... <= 0 ..." (or >= 180 deg) for each such point of `data`, for the fit's notes.
std::vector<std::string> damping_left_out(const HarmonicData& data);

struct RelativeResiduals {
  std::vector<double> stiffness;  // K_th / K_exp - 1
  std::vector<double> damping;    // d_th / d_exp - 1
};

// `model` must hold one point per data point, in the same order.
RelativeResiduals relative_residuals(const HarmonicData& data, const std::vector<HarmonicPoint>& model);
// Eq. 5.38 with weight k on stiffness (k = 0.5 gives half of eq. 5.1).
double phi(const RelativeResiduals& r, double stiffness_weight, double damping_weight);
double thesis_err(const RelativeResiduals& r);  // eq. 6.1

// Simulates the model at every data point (same order) with the given options.
std::vector<HarmonicPoint> simulate_at(const Network& network, const HarmonicData& data, const HarmonicOptions& options);

}  // namespace rheo::runtime
