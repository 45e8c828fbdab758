#include "runtime/fit/data_set_fit.hpp"

#include <algorithm>
#include <cmath>

namespace rheo::runtime {

DataSetFit data_set_fit(const Network& network, const FitDataSet& set, const HarmonicOptions& harmonic) {
  DataSetFit d;
  d.path = set.path;
  d.weight = set.weight;
  d.source = set.source;
  d.harmonic = set.is_harmonic();
  d.prediction = predict(network, set, FitMethod::exact, harmonic, nullptr);
  d.force_offset = {.given = set.force_offset.given, .free = set.force_offset.free, .value = d.prediction.force_offset};
  if (d.harmonic) {
    d.residuals = relative_residuals(set.harmonic(), d.prediction.points);
    d.measured_stiffness = set.harmonic().stiffness;
    d.measured_phase = set.harmonic().phase;
    d.phi = phi(d.residuals, 1.0, 1.0);
    d.err = thesis_err(d.residuals);
    return d;
  }
  const HistoryData& h = set.history();
  double sum = 0.0;
  for (std::size_t j = 0; j < h.force.size(); ++j) {
    const double r = (d.prediction.force[j] - h.force[j]) / h.force_scale;
    sum += r * r;
    d.worst = std::max(d.worst, std::abs(r));
  }
  d.err = std::sqrt(sum / static_cast<double>(h.force.size()));
  return d;
}

}  // namespace rheo::runtime
