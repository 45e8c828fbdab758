// The figures of a report, from its content:
//   per harmonic grid: dynamic stiffness and phase over frequency, a curve per amplitude, and
//   over amplitude, a curve per frequency (at most 8 curves: with more amplitudes or
//   frequencies, 8 spread evenly over them); only over the variable that varies when the other
//   has one value (a master curve at one amplitude, an amplitude sweep at one frequency). Then
//   storage K' = K cos(phase) and loss K'' = K sin(phase) over the first variable drawn; for
//   material data with its geometry (HarmonicComparison::material) as moduli E' = K'h/A,
//   E'' = K''h/A in MPa, amplitudes as strain = amplitude / h in %. Measured as markers, model
//   as lines; log axes where the values (the measured ones when there are some) span a factor
//   of 20 or more (svg_plot.hpp, scale_for), never for the phase. With measurements, residual maps of stiffness (K/K_exp - 1, %) and
//   phase (phase - phase_exp, deg).
//   per history: the hysteresis loop, force over displacement (at most 400 measured markers
//   and 4000 model points, evenly subsampled).
// With a baseline (an earlier model, e.g. before a diagnosis added an element) each model curve
// has a dashed twin for it, and the residual maps come twice: the model's, then the baseline's,
// each pair on one colour scale.
#pragma once

#include "runtime/report/report_content.hpp"
#include "runtime/report/residual_map.hpp"
#include "runtime/report/svg_plot.hpp"

#include <string>
#include <vector>

namespace rheo::runtime::report {

inline constexpr std::size_t kMaxCurves = 8;

// Which variables a grid's curves are drawn over: frequency unless only the amplitude varies,
// amplitude when it varies (both when both vary).
struct HarmonicAxes {
  bool over_frequency = true, over_amplitude = false;
};
HarmonicAxes harmonic_axes(const HarmonicComparison& grid);

// Ids are `prefix` + "-KIND", KIND in this order: stiffness-frequency, phase-frequency (over
// frequency), stiffness-amplitude, phase-amplitude (over amplitude), then storage-X, loss-X with
// X frequency when drawn over frequency, else amplitude (shown as strain for material data).
std::vector<Plot> harmonic_plots(const HarmonicComparison& grid, const std::string& prefix);
// Stiffness then phase (then stiffness and phase of the baseline); none without measurements.
std::vector<ResidualMap> residual_maps(const HarmonicComparison& grid);
Plot hysteresis_plot(const HistoryComparison& history, const std::string& id);

// The figure `--plot` writes, as a standalone SVG: the first harmonic grid's first figure
// (stiffness over frequency, or over amplitude when only the amplitude varies), else the first
// history's hysteresis loop. Throws UsageError when there is neither.
std::string primary_figure_svg(const ReportContent& content);

}  // namespace rheo::runtime::report
