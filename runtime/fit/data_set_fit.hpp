// How fitted parameters meet one measured data set: the exact response, its residuals and
// the summary measures a fit reports (err, eq. 6.1, for a harmonic table; the RMS and the
// largest force residual relative to max|F_exp| for a history), with the history's force
// offset (force_offset.hpp) as the prediction carries it.
#pragma once

#include "runtime/fit/fit_scoring.hpp"
#include "runtime/fit/force_offset.hpp"
#include "runtime/fit/objective.hpp"
#include "runtime/io/fit_data.hpp"
#include "runtime/network/network.hpp"

#include <string>
#include <vector>

namespace rheo::runtime {

struct DataSetFit {
  std::string path;
  double weight = 1.0;
  DataSource source;
  bool harmonic = true;
  Prediction prediction;                                   // exact response at the fitted parameters
  double phi = 0.0;                                        // harmonic: eq. 5.1
  double err = 0.0;                                        // harmonic: eq. 6.1; history: RMS of (F - F_exp) / max|F_exp|
  double worst = 0.0;                                      // history: max |F - F_exp| / max|F_exp|
  std::vector<double> measured_stiffness, measured_phase;  // harmonic: the data [N/mm], [rad]
  RelativeResiduals residuals;                             // harmonic: K/K_exp - 1, d/d_exp - 1
  FittedOffset force_offset;                               // history: its force offset, declared or fitted (force_offset.hpp)
};

// NETWORK's exact response to SET (free offsets at their least-squares value for it), its
// residuals, phi and err (harmonic), err and worst (history), and the offset without statistics.
DataSetFit data_set_fit(const Network& network, const FitDataSet& set, const HarmonicOptions& harmonic);

}  // namespace rheo::runtime
