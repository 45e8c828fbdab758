#include "runtime/fit/force_offset.hpp"

#include <stdexcept>

namespace rheo::runtime {

double force_offset(const FitDataSet& set, const std::vector<double>& network_force, Offsets mode) {
  if (set.is_harmonic() || mode == Offsets::none || !set.force_offset.given) return 0.0;
  if (!set.force_offset.free) return set.force_offset.value;
  if (mode == Offsets::declared) return 0.0;
  const std::vector<double>& measured = set.history().force;
  if (network_force.size() != measured.size() || measured.empty()) throw std::logic_error("force_offset: one predicted force per measured sample");
  double sum = 0.0;
  for (std::size_t j = 0; j < measured.size(); ++j) sum += measured[j] - network_force[j];
  return sum / static_cast<double>(measured.size());
}

void add_offset_statistics(FittedOffset& fitted, const FittedOffset& statistics) {
  fitted.standard_error = statistics.standard_error;
  fitted.identifiable = statistics.identifiable;
  fitted.correlation = statistics.correlation;
}

StatisticsWithOffsets statistics_with_offsets(const std::function<std::vector<Prediction>(const std::vector<double>&)>& predictions,
                                              const std::vector<FitDataSet>& data, const ScoreSettings& score, const std::vector<double>& z,
                                              const std::vector<bool>& logarithmic) {
  const std::size_t n = z.size();
  std::vector<std::size_t> free_sets;
  for (std::size_t f = 0; f < data.size(); ++f)
    if (!data[f].is_harmonic() && data[f].force_offset.given && data[f].force_offset.free) free_sets.push_back(f);
  // The network part at the optimum is computed once: the offsets' differences hold it.
  const std::vector<Prediction> at_optimum = predictions(z);
  std::vector<double> x = z;
  std::vector<bool> log_x = logarithmic;
  for (std::size_t f : free_sets) {
    x.push_back(force_offset(data[f], at_optimum.at(f).force, Offsets::applied));
    log_x.push_back(false);
  }
  const auto residuals = [&](const std::vector<double>& at) {
    const std::vector<double> at_z(at.begin(), at.begin() + static_cast<std::ptrdiff_t>(n));
    std::vector<Prediction> p = at_z == z ? at_optimum : predictions(at_z);
    for (std::size_t k = 0; k < free_sets.size(); ++k) {
      Prediction& q = p.at(free_sets[k]);
      for (double& force : q.force) force += at[n + k];
      q.force_offset = at[n + k];
    }
    std::vector<double> r;
    for (std::size_t f = 0; f < data.size(); ++f) append_residuals(data[f], p.at(f), score, r);
    return r;
  };
  return split_offsets(parameter_statistics(residuals, x, log_x), n, free_sets, data.size());
}

StatisticsWithOffsets split_offsets(const ParameterStatistics& all, std::size_t n, const std::vector<std::size_t>& free_sets, std::size_t data_sets) {
  StatisticsWithOffsets out;
  out.offsets.resize(data_sets);
  out.parameters = all;
  out.parameters.standard_error.resize(n);
  out.parameters.identifiable.resize(n);
  out.parameters.correlation.resize(n);
  for (auto& row : out.parameters.correlation) row.resize(n);
  for (std::size_t k = 0; k < free_sets.size(); ++k) {
    FittedOffset& o = out.offsets[free_sets[k]];
    o.standard_error = all.standard_error.at(n + k);
    o.identifiable = all.identifiable.at(n + k);
    o.correlation.assign(all.correlation.at(n + k).begin(), all.correlation.at(n + k).begin() + static_cast<std::ptrdiff_t>(n));
  }
  return out;
}

}  // namespace rheo::runtime
