// The global look of a candidate's refit (refit.hpp, stage 1): its new parameters sampled over
// the whole range the measurement can support, so that the local searches start in the basin
// of the data's optimum rather than where the screening's one-factor sizing left them.
//
// Supported ranges (internal units, within the parameter's bounds; log-uniform):
//   force (a yield force)   [F_low / 10, F_high]: F the measured force amplitudes K a of a
//                           harmonic table, or max|F|/100 .. max|F| of a history
//   time (a relaxation)     [1/(2 pi f_high) / 3, 3/(2 pi f_low)] over the measured frequencies
//                           (a history's loading rates)
//   length (a slip)         [a_low / 30, a_high] over the measured amplitudes
//   stiffness               [K / 300, 3 K], K the typical measured stiffness
//   mass (an inerter)       [K / 300 / w_high^2, 3 K / w_low^2], w = 2 pi f: the masses that
//                           resonate with some stiffness of that range within the measured
//                           frequencies (each parameter is sampled on its own, so a sampled
//                           pair may resonate outside them)
//   damping (a dashpot)     [K / 300 / (3 w_high), 9 K / w_low]: c = k tau over those
//                           stiffnesses and times (a column's channel: c = 2 zeta k / w)
//   others (positive)       a decade either side of the start
//   position                uniform over its bounds: a length whose bounds hold zero inside (a
//                           gap's centre, which a local search from a centred start cannot
//                           leave on harmonic data about zero: the objective is even in it)
// Other parameters whose bounds are not positive keep their start. The points are a Halton sequence
// (bases 2, 3, 5, ...) over the log box, each scored by the fit's objective (fit_scoring.hpp,
// method exact, free force offsets at their least-squares value).
#pragma once

#include "runtime/diagnosis/screen.hpp"
#include "runtime/fit/fit.hpp"

#include <vector>

namespace rheo::runtime::diagnosis {

struct SampledStart {
  std::vector<double> values;  // every model parameter
  double objective = 0.0;      // +inf where the network cannot be simulated
};

// [low, high] the data support for parameter INDEX of NETWORK (internal units), as above.
std::pair<double, double> supported_range(const Network& network, int index, const std::vector<FitDataSet>& data, const DataScales& scales);

// START (the screened element), then the best STARTS - 1 of SAMPLES points of the supported box
// of ADDED, best first, each scored.
std::vector<SampledStart> global_look(const Network& start, const std::vector<int>& added, const std::vector<FitDataSet>& data,
                                      const ScoreSettings& score, int samples, int starts);

}  // namespace rheo::runtime::diagnosis
