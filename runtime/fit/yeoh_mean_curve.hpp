// Yeoh constants from the mean shape of a static or quasi-static loop (section 5.3.1).
//
// Mean shape (Fig. 5.4): F_mean(u) = (F_load(u) + F_unload(u)) / 2 at common displacements.
// Yeoh law (eq. 3.3, 5.28): F = [2u 4u^3 6u^5] [D10 D20 D30]^T, D10 [N/mm], D20 [N/mm^3],
// D30 [N/mm^5]. Least squares over the mean curve (5.29-5.32): min |A d - F_mean|, solved by
// column-pivoted Householder QR on A with its columns scaled to unit norm (the normal equations
// 5.31 square the condition number). Shape transfer (5.33-5.36): A = D20/D10, B = D30/D10 from
// the least-squares fit, D10 = K_e/2 from the dynamic fit, D20 = A D10, D30 = B D10.
//
// Why the mean of the branches is the elastic law: in a parallel model of an elastic spring,
// friction elements and Maxwell elements driven at constant speed v, a friction element that
// has fully slipped carries +F_y on loading and -F_y on unloading, and a Maxwell element
// +-c v once its reversal transient e^{-|u - u_turn| / (v t_r)} has died; both cancel in the
// mean. Near a turning point u_turn, at s = |u_turn - u|, the mean carries instead
//   sign(u_turn) [ sum_q max(0, F_y^q - K_p^q s / 2) + sum_j c_j v e^{-s / (v t_r^j)} ]  [N]
// (friction element q reverses over s = 2 u_s^q), which is why the turning regions are
// excluded (`turning_margin` below).
#pragma once

#include "lang/model.hpp"

#include "runtime/io/history_csv.hpp"

#include <array>
#include <utility>
#include <vector>

namespace rheo::runtime {

struct LoopSamples {
  std::vector<double> displacement;  // mm
  std::vector<double> force;         // N
};

struct MeanCurve {
  std::vector<double> displacement;  // mm, strictly increasing
  std::vector<double> force;         // N
};

struct YeohConstants {
  double d10, d20, d30;  // N/mm, N/mm^3, N/mm^5
};

// The "displacement" and "force" columns of a time history table (history_csv.hpp), in row
// order. DataError naming the file when either column is missing.
LoopSamples loop_samples_from_table(const Table& table);

// The last full cycle of the largest amplitude in a history of cycles of several amplitudes
// (e.g. the static test: triangles of decreasing amplitude, 2 cycles each; the last cycle of an
// amplitude is the settled one). Cycles are cut at upward crossings of the level
// c = (max u + min u) / 2: sample k starts a cycle when u_k <= c < u_{k+1}, and the cycle runs to
// the next such sample, inclusive (so the loop is closed); the record's tail counts as a cycle
// when its last sample is back at c (within 1e-6 of the range). The cycle amplitude is
// (max u - min u) / 2 over the cycle; the largest are those within 0.1 % of the maximum.
// DataError when the record holds no full cycle.
LoopSamples largest_loop(const LoopSamples& history);
// Its first and last sample (inclusive) in the displacement record U, for callers that cut
// the force themselves (a long history's, without copying it whole).
std::pair<std::size_t, std::size_t> largest_cycle(const std::vector<double>& u);

// The mean curve of the largest closed loop in `loop` (one or more cycles, any sampling):
//  1. u_max, u_min and the range R = u_max - u_min over all samples.
//  2. The record is split into maximal monotone runs (equal consecutive displacements extend a
//     run). The loading branch is the last non-decreasing run that reaches both u_min and u_max
//     (within 1e-3 R); the unloading branch the last non-increasing one. Where no single run
//     does and the record is closed (last displacement within 1e-3 R of the first), the last
//     run followed by the first one (its first sample, the repeat of the closing one, dropped)
//     is used: a single cycle 0 -> +A -> 0 -> -A -> 0 has its loading branch split that way.
//     A branch built from monotone runs is single-valued: samples at the same displacement
//     are averaged.
//  3. Turning regions: displacements within turning_margin * R of u_min or u_max are dropped
//     (default 5 % of the peak-to-peak range at each end, 0.1 A for a symmetric loop of
//     amplitude A). This removes the reversal zone above when 2 max u_s < turning_margin * R;
//     for specimen D (max u_s = 0.111 mm) and A = 6.25 mm that zone is 1.8 % of R.
//  4. The common displacements are the union of both branches' samples in the kept range
//     (duplicates within 1e-12 R merged); each branch is interpolated linearly there (exact at
//     its own samples, so a triangle sampled alike on both branches involves no interpolation).
// DataError when no full loading and unloading branch exist, or fewer than 3 common
// displacements remain; std::logic_error for mismatched sizes or a margin outside [0, 0.5).
MeanCurve mean_curve(const LoopSamples& loop, double turning_margin = 0.05);

// Eqs. 5.29-5.32. std::logic_error when the curve has fewer than 3 points or sizes differ;
// NumericalError when A has rank < 3 (e.g. fewer than 3 distinct |u| > 0).
YeohConstants fit_yeoh_least_squares(const MeanCurve& curve);

// Eqs. 5.33-5.36. elastic_stiffness = K_e [N/mm] of the dynamic fit, > 0 (std::logic_error
// otherwise); NumericalError when least_squares.d10 = 0 (the ratios of 5.33 are undefined).
YeohConstants yeoh_from_shape(const YeohConstants& least_squares, double elastic_stiffness);

// A start value of one yeoh constant from a loop record.
struct YeohStartValue {
  int parameter = -1;      // index into the model's parameters
  double value = 0.0;      // internal units, clamped into the parameter's bounds when it has them
  double unclamped = 0.0;  // the least-squares value (eq. 5.32)
  bool free = false;       // in the fit's free set; a fixed constant keeps its value and is not started
};

// Start values of the yeoh spring whose constants are the parameters YEOH (D10, D20, D30) of
// MODEL: least squares on the mean curve of the largest loop of RECORD (eqs. 5.28-5.32). Throws
// DataError (from largest_loop, mean_curve) when RECORD holds no usable loop.
std::array<YeohStartValue, 3> yeoh_start_values(const lang::CheckedModel& model, const std::array<int, 3>& yeoh, const std::vector<int>& free,
                                                const LoopSamples& record);
// The same from the largest loop already cut (largest_loop, largest_cycle).
std::array<YeohStartValue, 3> yeoh_start_values_of_loop(const lang::CheckedModel& model, const std::array<int, 3>& yeoh,
                                                        const std::vector<int>& free, const LoopSamples& loop);

}  // namespace rheo::runtime
