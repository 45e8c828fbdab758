// Parameter identification against harmonic data with the exact steady-state response.
//
// The free parameters (declared with bounds) are searched by NLopt; a parameter whose bounds
// are positive is searched in log space, z = ln p, so that relative changes weigh alike.
// Derived parameters (c = k tau, fy = k uy) follow their free inputs. The objective is phi of
// eq. 5.38 (weights k on stiffness, 1 - k on damping; eq. 5.1 with both 1).
#pragma once

#include "runtime/harmonic_data.hpp"
#include "runtime/network.hpp"
#include "runtime/objective.hpp"
#include "runtime/optimizer.hpp"

namespace rheo::runtime {

struct FitSettings {
  OptimizerSettings optimizer;
  HarmonicOptions harmonic;
  double stiffness_weight = 1.0;
  double damping_weight = 1.0;
};

struct FitResult {
  Network network;              // the model with the fitted values
  std::vector<int> free;        // indices of the fitted parameters
  double phi = 0.0;             // at the optimum, with the settings' weights
  double err = 0.0;             // eq. 6.1
  OptimizationResult optimization;
};

// Throws std::invalid_argument when the model has no free parameter (declare one with bounds,
// `k = 300 N/mm in [10, 5000]`).
FitResult fit_harmonic(const Network& start, const HarmonicData& data, const FitSettings& settings);

}  // namespace rheo::runtime
