// The harmonic and time-history protocols on the variable-step backend (dae_integrator.hpp).
//
// Harmonic: the drive is the exact sine u0 sin(w t) from rest; the force is sampled at
// steps_per_cycle points of each cycle (interpolated by IDA, not stepped), and cycles repeat
// until the state at the end of a cycle equals the state at its start within
// max(tolerance, 100 rtol) relative (positions to u0, forces to F^, velocities to w u0).
// History: the drive is linear between samples, as on the fixed-step backend, and each sample
// is a restart of the integration.
#pragma once

#include "runtime/dae/dae_integrator.hpp"
#include "runtime/core/drive.hpp"
#include "runtime/core/harmonic_point.hpp"

#include <string>
#include <vector>

namespace rheo::runtime {

// Relative tolerance of IDA for the protocols (absolute tolerances scale with the drive).
inline constexpr double kDaeRelativeTolerance = 1e-8;

// PRELOAD p [mm]: the drive is p + u0 sin(w t), from START (the relaxed state at p; required
// where p != 0).
HarmonicPoint dae_harmonic_point(const Network& network, double amplitude, double frequency, const HarmonicOptions& options,
                                 DaeStatistics* statistics = nullptr, double preload = 0.0, const StartAtRest* start = nullptr);

// From rest, or from START where given (DaeHistoryStepper sample by sample).
History dae_history(const Network& network, const Drive& drive, bool elements, DaeStatistics* statistics = nullptr,
                    const StartAtRest* start = nullptr);

// A force scale [N] for a length scale [mm] and a rate scale [mm/s]: what the network carries,
// to set IDA's absolute force tolerance. Members in parallel add; a series chain carries what
// its weakest member carries (so a 1e9 N/mm spring in series with a soft arm does not inflate
// the scale and loosen the tolerance 1e9-fold). Per element: spring k L, yeoh 2|D10| L, dashpot
// c v, quadratic dashpot cq v^2, Maxwell min(k L, c v), friction min(k L, fy), slider fy,
// inerter b (v/L)^2 L, Bouc-Wen min(fy, k L); a gap is rigid in contact. Never below 1e-6 N.
double dae_force_scale(const Network& network, double length, double rate);

// IDA's Newton convergence coefficient for a network whose stiffest spring carries
// F_k = k L [N] at the length scale: 0.33 F / F_k, in [1e-6, 0.33]. Internal node positions
// are unknowns, so a position error dx is a force error k dx in that spring; with the default
// coefficient, a 1e9 N/mm spring in series with a 1 N/mm arm put 1e-2 errors in K.
double dae_newton_tolerance(const DaeGraph& graph, double length, double force_scale);

// What to add to a failure's message: IDA's own message when its corrector fails says nothing
// about why, and a yeoh in series that softens (its tangent reaching zero,
// YeohLaw::softening_elongation) is the usual reason. Empty where no yeoh softens.
std::string dae_softening_hint(const Network& network);

// Node positions [mm] of a start at rest at U0 [mm] from the elements' state START (Topology::probes
// order, which the graph's probes follow: both walk the model's tree in source order).
std::vector<double> dae_start_positions(const Network& network, const DaeGraph& graph, double u0, const StartAtRest& start);

}  // namespace rheo::runtime
