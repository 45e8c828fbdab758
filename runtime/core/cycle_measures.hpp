// Characterisation of one steady-state cycle of a harmonic test u = u0 sin(w t).
//
// Thesis definition (eqs. 1.2, 5.26, 5.27), the default:
//   F^ = (max F - min F) / 2,   K = F^ / u0,   U = loop integral of F du = pi u0^2 K''_1
//   (exact for the sine drive, du = u0 w cos(w t) dt; spectrally accurate for smooth loops),
//   d = U / (pi F^ u0),         phase = asin(d)        (d > 1 is clamped to 90 deg and flagged).
// First harmonic (what many test rigs report):
//   F1 = (2/T) int F(t) e^{-i w t} dt = u0 (K' ... ) so that K* = K' + i K'' with
//   K' = (2/(N u0)) sum F_k sin(w t_k),  K'' = (2/(N u0)) sum F_k cos(w t_k),
//   K = |K*|, phase = arg K*.
// For a linear network both equal |K*(w)| and arg K*(w). Storage/loss: K cos(phase), K sin(phase).
// Samples: N equally spaced over exactly one period, periodic (sample N would repeat sample 0).
#pragma once

#include "lang/protocol_settings.hpp"

#include <span>

namespace rheo::runtime {

using lang::HarmonicDefinition;  // the `definition` setting's vocabulary

struct CycleMeasures {
  double force_amplitude = 0.0;  // F^ [N]
  double energy = 0.0;           // U, dissipated per cycle [N*mm]
  double stiffness = 0.0;        // K [N/mm]
  double damping = 0.0;          // d = U/(pi F^ u0) (thesis) or sin(phase) (first harmonic)
  double phase = 0.0;            // [rad]; thesis: asin(d), or pi - asin(d) where K'_1 < 0 (mass-dominated)
  double storage = 0.0;          // K cos(phase) [N/mm]
  double loss = 0.0;             // K sin(phase) [N/mm]
  bool damping_clamped = false;  // thesis definition with d > 1 (e.g. a bare slider: d = 4/pi)
};

struct CycleSamples {
  std::span<const double> phase;         // w t_k [rad]
  std::span<const double> displacement;  // u_k [mm]
  std::span<const double> force;         // F_k [N]
};

// Loop area of any closed loop by the periodic trapezoidal rule (second order): sum (F_k + F_{k+1})/2 (u_{k+1} - u_k) [N*mm].
double loop_energy(const CycleSamples& samples);

CycleMeasures measure_cycle(const CycleSamples& samples, double amplitude, HarmonicDefinition definition);

// The measures of a cycle given F^ [N] and the first harmonic K'_1, K''_1 [N/mm] at amplitude
// u0 [mm] (U = pi u0^2 K''_1), by either definition.
CycleMeasures measures_from(double force_amplitude, double storage1, double loss1, double amplitude, HarmonicDefinition definition);

}  // namespace rheo::runtime
