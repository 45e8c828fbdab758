// Harmonic test protocol: steady-state response to u = p + u0 sin(2 pi f t) (p the preload) over a grid of
// amplitudes x frequencies (thesis Table 4.5), characterised per cycle_measures.hpp.
//
// Steady state is detected, not assumed. Each point starts from the exact periodic state where
// one is known in closed form for the sampled drive:
//   Maxwell element in the root block, drive sampled with theta = w dt = 2 pi / N:
//     F_0 = b u0 Im[(e^{i theta} - 1) / (e^{i theta} - a)]   (a, b of the exact update, eq. 2.7;
//     the fixed point of the one-cycle map, tends to k u0 w tau / (1 + w^2 tau^2) as N -> inf);
//   friction element in the root block: F_0 = min(fy, k u0 - fy) if u0 > fy/k, else 0;
//   subtrees start at rest.
// Cycles are repeated until the state at the end of a cycle equals the state at its start
// within `tolerance` (relative to F^ for forces and u0 for elongations), the error being
// extrapolated from the per-cycle contraction when the state is still moving; a point that has
// not converged after `max_cycles` is reported as such. When that contraction is geometric and
// steady (a slow mode, e.g. a subtree's Maxwell element with tau >> period, starting from rest),
// the state skips the rest of the geometric tail, s + (s - s_prev) rho / (1 - rho); convergence
// is still judged on simulated cycles after the skip.
// Forces are sampled at the step ends; for networks whose force jumps with the drive rate
// (a dashpot with no spring in series) at the step midpoints instead, which keeps the
// characterisation second order in the step.
#pragma once

#include "runtime/core/harmonic_point.hpp"
#include "runtime/network/network.hpp"
#include "runtime/protocols/solver_choice.hpp"

#include <vector>

namespace rheo::runtime {

// Whether simulate_harmonic_point takes the closed form for this network and these options:
// not with steady_state = time_stepping or solver = sundials; piecewise-linear subtrees
// (event-driven, pwl_periodic.hpp) with solver = auto or steady_state = closed_form, while an
// explicit solver = fixed keeps their time stepping (a budget the user chose).
bool uses_closed_form(const Network& network, const HarmonicOptions& options);

// Throws std::logic_error unless amplitude and frequency are positive and finite (the
// language and data readers refuse others at their file:line:col first).
// PRELOAD p [mm]: the drive is u = p + u0 sin(2 pi f t) from the network relaxed at p
// (stepping/relaxed_state.hpp); the closed form takes it where it can (periodic_closed_form.hpp),
// time stepping and IDA otherwise.
HarmonicPoint simulate_harmonic_point(const Network& network, double amplitude, double frequency, const HarmonicOptions& options,
                                      double preload = 0.0);

// Amplitude-major order (all frequencies of the first amplitude first), as in the data files.
std::vector<HarmonicPoint> simulate_harmonic_grid(const Network& network, const std::vector<double>& amplitudes,
                                                  const std::vector<double>& frequencies, const HarmonicOptions& options, double preload = 0.0);

}  // namespace rheo::runtime
