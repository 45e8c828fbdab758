// Where a fitted model and the measurement disagree, in numbers people can check.
//
// Harmonic points: r_K = K/K_exp - 1 and r_d = d/d_exp - 1 (the residuals of eq. 5.1) are split
// over the amplitude x frequency grid into an additive part, m + A(amplitude) + F(frequency)
// (least squares by back-fitting, so gaps in the grid are allowed), and the rest, the
// interaction I(amplitude, frequency). The shares of sum(r_K^2 + r_d^2) held by A, F and I
// tell whether the missing behaviour depends on amplitude alone, on frequency alone, or on
// both together (the coupled dependence the thesis' uncoupled models cannot show, ch. 6.3.3).
// Histories: the RMS and largest force residual relative to max|F_exp|.
#pragma once

#include "runtime/fit/fit.hpp"

#include <vector>

namespace rheo::runtime::diagnosis {

struct HarmonicPatterns {
  int points = 0;
  double stiffness_rms = 0.0;    // RMS of r_K [-]
  double phase_rms = 0.0;        // RMS of model - measured phase [rad]
  double amplitude_share = 0.0;  // share of sum(r_K^2 + r_d^2) in A, F, I (the mean takes the rest)
  double frequency_share = 0.0;
  double interaction_share = 0.0;
  // Degrees of freedom the grid leaves the interaction: measured (amplitude, frequency) cells
  // less the additive model's levels, C - (n_a + n_f - components) over the graph of levels
  // joined by cells. 0 for one amplitude sweep and one frequency sweep (an L), a line or a
  // single point: every residual then fits A + F and the interaction is not measured.
  int interaction_dof = 0;
  bool interaction_measured() const { return interaction_dof > 0; }
  struct Worst {
    double amplitude = 0.0, frequency = 0.0;  // [mm], [Hz]
    double residual = 0.0;                    // r_K [-], or model - measured phase [rad]
  };
  Worst worst_stiffness, worst_phase;  // the points of the largest |r_K| and phase residual
  double phase_peak_frequency = 0.0;   // frequency where the measured phase most exceeds the model's, averaged over amplitudes [Hz]
  double phase_peak = 0.0;             // that excess [rad]
};

struct HistoryPatterns {
  std::string path;
  double rms = 0.0;                 // RMS (F - F_exp) / max|F_exp|
  double worst = 0.0;               // max |F - F_exp| / max|F_exp|
  double worst_displacement = 0.0;  // u there [mm]
};

struct ResidualPatterns {
  bool has_harmonic = false;
  HarmonicPatterns harmonic;  // over every harmonic file
  std::vector<HistoryPatterns> histories;
};

ResidualPatterns residual_patterns(const FitResult& fit, const std::vector<FitDataSet>& data);

}  // namespace rheo::runtime::diagnosis
