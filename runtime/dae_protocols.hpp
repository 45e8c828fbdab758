// The harmonic and time-history protocols on the variable-step backend (dae_integrator.hpp).
//
// Harmonic: the drive is the exact sine u0 sin(w t) from rest; the force is sampled at
// steps_per_cycle points of each cycle (interpolated by IDA, not stepped), and cycles repeat
// until the state at the end of a cycle equals the state at its start within
// max(tolerance, 100 rtol) relative (positions to u0, forces to F^, velocities to w u0).
// History: the drive is linear between samples, as on the fixed-step backend, and each sample
// is a restart of the integration.
#pragma once

#include "runtime/dae_integrator.hpp"
#include "runtime/drives.hpp"
#include "runtime/harmonic.hpp"

namespace rheo::runtime {

// Relative tolerance of IDA for the protocols (absolute tolerances scale with the drive).
inline constexpr double kDaeRelativeTolerance = 1e-8;

HarmonicPoint dae_harmonic_point(const Network& network, double amplitude, double frequency, const HarmonicOptions& options,
                                 DaeStatistics* statistics = nullptr);

History dae_history(const Network& network, const Drive& drive, bool elements, DaeStatistics* statistics = nullptr);

// A force scale [N] for a length scale [mm]: what the network's springs and sliders carry.
double dae_force_scale(const DaeGraph& graph, double length);

}  // namespace rheo::runtime
