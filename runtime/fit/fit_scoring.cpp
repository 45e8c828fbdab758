#include "runtime/fit/fit_scoring.hpp"
#include "runtime/protocols/run_history.hpp"

#include "runtime/core/parallel_for.hpp"
#include "runtime/fit/force_offset.hpp"
#include "runtime/fit/objective.hpp"

#include <cmath>
#include <complex>
#include <stdexcept>

namespace rheo::runtime {

Prediction predict(const Network& network, const FitDataSet& set, FitMethod method, const HarmonicOptions& harmonic,
                   const ThesisCorrection* correction, Offsets offsets) {
  Prediction p;
  if (!set.is_harmonic()) {
    p.force = history_force(network, set.history().drive, harmonic.solver);
    p.force_offset = force_offset(set, p.force, offsets);
    for (double& f : p.force) f += p.force_offset;
    return p;
  }
  const HarmonicData& data = set.harmonic();
  if (method == FitMethod::exact) {
    p.points = simulate_at(network, data, harmonic);
    return p;
  }
  p.points = approximate_harmonic(network, data.amplitude, data.frequency, harmonic.threads);
  if (method == FitMethod::corrected) {
    if (!correction) throw std::logic_error("the corrected method needs correction factors");
    apply_correction(*correction, p.points);
  }
  return p;
}

void append_residuals(const FitDataSet& set, const Prediction& prediction, const ScoreSettings& settings, std::vector<double>& out) {
  if (!set.is_harmonic()) {
    const HistoryData& h = set.history();
    const double scale = std::sqrt(set.weight / static_cast<double>(h.force.size())) / h.force_scale;
    for (std::size_t j = 0; j < h.force.size(); ++j) out.push_back(scale * (prediction.force[j] - h.force[j]));
    return;
  }
  const HarmonicData& d = set.harmonic();
  // Point i's two terms at first + 2i and first + 2i + 1, the points spread over the threads (a
  // single evaluation's residuals would otherwise run on one thread between its points and the
  // search's next step); each term is computed alike on any thread.
  const std::size_t first = out.size();
  out.resize(first + 2 * d.size());
  parallel_for(d.size(), settings.harmonic.threads, [&](std::size_t i) {
    const CycleMeasures& m = prediction.points[i].measures;
    const double point_scale = harmonic_point_scale(set, i);
    double* terms = out.data() + first + 2 * i;
    if (settings.objective == FitObjective::phi) {
      terms[0] = point_scale * std::sqrt(settings.stiffness_weight) * stiffness_residual(m.stiffness, m.phase, d.stiffness[i], d.phase[i]);
      terms[1] = point_scale * std::sqrt(settings.damping_weight) * damping_residual(m.phase, d.phase[i]);
    } else {
      const std::complex<double> model = std::polar(m.stiffness, m.phase), measured = std::polar(d.stiffness[i], d.phase[i]);
      const std::complex<double> r = (model - measured) / d.stiffness[i];
      terms[0] = point_scale * r.real();
      terms[1] = point_scale * r.imag();
    }
  });
}

}  // namespace rheo::runtime
