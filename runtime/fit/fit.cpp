#include "runtime/fit/fit.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/fit/data_set_fit.hpp"
#include "runtime/fit/fit_coordinates.hpp"
#include "runtime/fit/fit_report.hpp"
#include "runtime/fit/force_offset.hpp"
#include "runtime/fit/force_scales.hpp"
#include "runtime/fit/harmonic_jacobian.hpp"
#include "runtime/fit/history_jacobian.hpp"
#include "runtime/fit/history_scoring.hpp"
#include "runtime/fit/separable_fit.hpp"
#include "runtime/fit/parameter_bounds.hpp"
#include "runtime/fit/yeoh_mean_curve.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

namespace rheo::runtime {
namespace {

// Predictions of all files for one method (and, for `corrected`, its factors).
std::vector<Prediction> predictions(const Network& network, const std::vector<FitDataSet>& data, const ScoreSettings& score, FitMethod method,
                                    const std::vector<ThesisCorrection>& corrections, Offsets offsets) {
  std::vector<Prediction> p;
  std::size_t harmonic_index = 0;
  for (const FitDataSet& set : data) {
    const ThesisCorrection* correction = set.is_harmonic() && method == FitMethod::corrected ? &corrections.at(harmonic_index) : nullptr;
    if (set.is_harmonic()) ++harmonic_index;
    p.push_back(predict(network, set, method, score.harmonic, correction, offsets));
  }
  return p;
}

// Residual vector of all files, free force offsets eliminated (force_offset.hpp).
std::vector<double> residuals(const Network& network, const std::vector<FitDataSet>& data, const ScoreSettings& score, FitMethod method,
                              const std::vector<ThesisCorrection>& corrections) {
  std::vector<double> r;
  const std::vector<Prediction> p = predictions(network, data, score, method, corrections, Offsets::applied);
  for (std::size_t f = 0; f < data.size(); ++f) append_residuals(data[f], p[f], score, r);
  return r;
}

std::vector<ThesisCorrection> corrections_at(const Network& network, const std::vector<FitDataSet>& data, const HarmonicOptions& harmonic) {
  std::vector<ThesisCorrection> result;
  for (const FitDataSet& set : data)
    if (set.is_harmonic())
      result.push_back(thesis_correction(predict(network, set, FitMethod::approximate, harmonic, nullptr).points,
                                         predict(network, set, FitMethod::exact, harmonic, nullptr).points));
  return result;
}

// True when every file is a harmonic table and the network has the structure of the thesis
// approximation (springs, yeoh, Maxwell and friction elements in parallel).
bool approximation_applies(const Network& network, const std::vector<FitDataSet>& data) {
  for (const FitDataSet& set : data)
    if (!set.is_harmonic() || set.harmonic().size() == 0) return false;
  return approximation_misfit(network).empty();
}

// The yeoh start of FitSettings::yeoh_start_from_history: new start values, or the old ones;
// the parameters it started are added to STARTED.
std::vector<double> yeoh_start(const Network& start, const std::vector<int>& free, const std::vector<FitDataSet>& data,
                               std::vector<std::string>& notes, std::vector<int>& started_parameters) {
  std::vector<double> values = start.parameters();
  const Topology& t = start.topology();
  if (t.yeohs.size() != 1) return values;
  const HistoryData* widest = nullptr;
  double widest_range = 0.0, offset = 0.0;
  for (const FitDataSet& set : data)
    if (!set.is_harmonic()) {
      const auto& u = set.history().drive.displacement;
      const auto [lo, hi] = std::minmax_element(u.begin(), u.end());
      if (*hi - *lo > widest_range) widest = &set.history(), widest_range = *hi - *lo, offset = force_offset(set, {}, Offsets::declared);
    }
  if (!widest) return values;
  std::array<YeohStartValue, 3> started;
  try {
    // The largest loop alone is copied (a long history is not), its force the network's part:
    // less a declared offset.
    const auto [first, last] = largest_cycle(widest->drive.displacement);
    const auto from = static_cast<std::ptrdiff_t>(first), to = static_cast<std::ptrdiff_t>(last) + 1;
    LoopSamples loop{{widest->drive.displacement.begin() + from, widest->drive.displacement.begin() + to},
                     {widest->force.begin() + from, widest->force.begin() + to}};
    for (double& f : loop.force) f -= offset;
    started = yeoh_start_values_of_loop(start.model(), t.yeohs.front(), free, loop);
  } catch (const UserError& e) {  // the record holds no usable loop: the start stays as written
    notes.push_back(fmt::format("no yeoh start from {}: {}", widest->path, e.what()));
    return values;
  }
  for (const YeohStartValue& s : started) {
    if (!s.free) continue;
    const lang::Parameter& p = start.model().parameters[static_cast<std::size_t>(s.parameter)];
    values[static_cast<std::size_t>(s.parameter)] = std::clamp(s.unclamped, p.lower, p.upper);
    started_parameters.push_back(s.parameter);
    notes.push_back(fmt::format("start {} = {:.6g} {} from the mean curve of {} (eq. 5.32)", p.path,
                                in_written_unit(p, values[static_cast<std::size_t>(s.parameter)]), written_unit(p), widest->path));
  }
  return values;
}

}  // namespace

std::vector<int> bounded_parameters(const Network& network) {
  std::vector<int> free;
  const auto& parameters = network.model().parameters;
  for (std::size_t i = 0; i < parameters.size(); ++i)
    if (parameters[i].free) free.push_back(static_cast<int>(i));
  return free;
}

namespace {

// The searches of one fit, in the coordinates of COORDINATES, each adding its counts and status
// to RESULT: one search by method, and the staged strategies of the corrected method (Table
// 5.1) and of the exact one with the corrected fit as a surrogate start.
class StagedSearch {
 public:
  StagedSearch(const Coordinates& coordinates, const std::vector<FitDataSet>& data, const FitSettings& settings, FitResult& result)
      : coordinates_(coordinates), data_(data), settings_(settings), result_(result) {}

  // The residual vector of METHOD at z (for `corrected`, with the factors found so far).
  std::function<std::vector<double>(const std::vector<double>&)> residuals_for(FitMethod method) const {
    return [this, method](const std::vector<double>& z) { return residuals(coordinates_.network(z), data_, settings_.score, method, corrections_); };
  }
  // The predictions of METHOD at z with the declared offsets only (for statistics_with_offsets).
  std::function<std::vector<Prediction>(const std::vector<double>&)> predictions_for(FitMethod method) const {
    return [this, method](const std::vector<double>& z) {
      return predictions(coordinates_.network(z), data_, settings_.score, method, corrections_, Offsets::declared);
    };
  }

  // One search of METHOD from FROM with at most BUDGET evaluations (at least 1) and, under a
  // time limit, at most TIME_SHARE of the time left.
  std::vector<double> run(FitMethod method, const std::vector<double>& from, int budget, std::vector<std::vector<double>> extra_starts = {},
                          double time_share = 1.0) {
    const Residuals r = residuals_for(method);
    SearchSettings search = settings_.search;
    search.max_evaluations = std::max(1, budget);
    search.threads = settings_.score.harmonic.threads;  // each evaluation builds its own network: safe at once
    if (search.deadline && time_share < 1.0) {
      const auto now = std::chrono::steady_clock::now();
      if (*search.deadline > now)
        search.deadline = now + std::chrono::duration_cast<std::chrono::steady_clock::duration>((*search.deadline - now) * time_share);
    }
    search.extra_starts.insert(search.extra_starts.end(), extra_starts.begin(), extra_starts.end());
    if (settings_.sensitivities && residual_jacobian_applies(coordinates_.network(from), data_, settings_.score, method))
      search.jacobian = [this](const std::vector<double>& z) { return residual_jacobian(coordinates_, z, data_, settings_.score).jacobian; };
    // A long history's residuals are never held: phi and each Jacobian streamed (history_jacobian.hpp).
    // The bytes of the differenced Jacobian, 8 m n for m residuals in n coordinates.
    const bool by_value = method == FitMethod::exact && !search.jacobian && all_histories(data_) &&
                          sizeof(double) * history_residual_count(data_) * from.size() > settings_.whole_jacobian_bytes;
    if (by_value)
      search.reduced_jacobian = [this](const std::vector<double>& z, const std::vector<double>& steps) -> std::optional<ReducedJacobian> {
        std::optional<ReducedHistoryJacobian> reduced = reduced_history_jacobian(
            [this](const std::vector<double>& at) { return coordinates_.network(at); }, data_, settings_.score, z, steps);
        if (!reduced) return std::nullopt;
        return ReducedJacobian{std::move(reduced->r), std::move(reduced->c), std::move(reduced->moved_values)};
      };
    const Objective phi = [this](const std::vector<double>& z) { return history_phi(coordinates_.network(z), data_, settings_.score); };
    const SearchResult found = by_value
                                   ? search_least_squares_by_value(phi, history_residual_count(data_), from, coordinates_.lower, coordinates_.upper,
                                                                   coordinates_.logarithmic, search, settings_.progress, settings_.interrupt)
                                   : search_least_squares(r, from, coordinates_.lower, coordinates_.upper, coordinates_.logarithmic, search,
                                                          settings_.progress, settings_.interrupt);
    result_.evaluations += found.evaluations;
    result_.non_finite += found.non_finite;
    if (result_.first_failure.empty()) result_.first_failure = found.first_failure;
    result_.status = found.status;
    result_.interrupted = result_.interrupted || found.interrupted;
    result_.time_limited = result_.time_limited || found.out_of_time;
    result_.objective = found.value;
    return found.z;
  }

  // Variable projection (separable_fit.hpp): the force scales at positions SCALES of the free
  // parameters are solved exactly for every shape the search visits; the search runs over the
  // shape parameters only (none: one solve is the fit). Its budget is in model evaluations.
  std::vector<double> separable(const std::vector<int>& scales) {
    std::vector<int> scale_parameters, shape;
    std::vector<double> lower, upper;
    const auto& parameters = coordinates_.free();
    for (std::size_t j = 0; j < parameters.size(); ++j) {
      if (std::find(scales.begin(), scales.end(), static_cast<int>(j)) == scales.end()) {
        shape.push_back(static_cast<int>(j));
        continue;
      }
      const lang::Parameter& p = coordinates_.model().parameters[static_cast<std::size_t>(parameters[j])];
      scale_parameters.push_back(parameters[j]);
      lower.push_back(p.lower);
      upper.push_back(p.upper);
    }
    auto solved_at = [&](const std::vector<double>& z) {
      const ScaleSolution s = solve_scales(coordinates_.network(z), scale_parameters, lower, upper, data_, settings_.score);
      result_.evaluations += s.evaluations;
      return s;
    };
    if (shape.empty()) {
      const ScaleSolution s = solved_at(coordinates_.z0);
      result_.objective = s.objective;
      result_.status = "SCALES_SOLVED";
      return coordinates_.z_of(s.values);
    }
    auto full = [&](const std::vector<double>& shape_z) {
      std::vector<double> z = coordinates_.z0;
      for (std::size_t i = 0; i < shape.size(); ++i) z[static_cast<std::size_t>(shape[i])] = shape_z[i];
      return z;
    };
    std::vector<double> start, shape_lower, shape_upper;
    std::vector<bool> shape_log;
    for (int j : shape) {
      const auto u = static_cast<std::size_t>(j);
      start.push_back(coordinates_.z0[u]);
      shape_lower.push_back(coordinates_.lower[u]);
      shape_upper.push_back(coordinates_.upper[u]);
      shape_log.push_back(coordinates_.logarithmic[u]);
    }
    // The best solve is kept, so the search's best point needs no second solve.
    ScaleSolution best{.values = {}, .objective = std::numeric_limits<double>::infinity()};
    const Objective objective = [&](const std::vector<double>& shape_z) {
      ScaleSolution s = solved_at(full(shape_z));
      const double value = s.objective;
      if (value < best.objective) best = std::move(s);
      return value;
    };
    SearchSettings search = settings_.search;
    search.max_evaluations = std::max(1, total() / static_cast<int>(scales.size() + 1));
    search.threads = 1;  // the objective keeps the best solve and counts: one evaluation at a time
    search.extra_starts.clear();
    const SearchResult found = runtime::search(objective, start, shape_lower, shape_upper, shape_log, search, settings_.progress,
                                               settings_.interrupt);
    result_.non_finite += found.non_finite;
    if (result_.first_failure.empty()) result_.first_failure = found.first_failure;
    result_.status = found.status;
    result_.interrupted = found.interrupted;
    result_.time_limited = found.out_of_time;
    result_.objective = best.objective;
    return best.values.empty() ? coordinates_.z0 : coordinates_.z_of(best.values);
  }

  // Table 5.1: analytical part, numerical part (5.2, 5.3), calibrated analytical part (5.4).
  // Sets FINAL_METHOD to the method the returned z was fitted with.
  std::vector<double> corrected(FitMethod& final_method) {
    std::vector<double> z = run(FitMethod::approximate, coordinates_.z0, total() / 2, {}, 0.3);
    if (result_.interrupted) {
      final_method = FitMethod::approximate;
      return z;
    }
    result_.time_limited = false;  // its share ran out, not the fit's time
    corrections_ = corrections_at(coordinates_.network(z), data_, settings_.score.harmonic);
    return run(FitMethod::corrected, z, total() - result_.evaluations);
  }

  // The corrected approximation is a cheap surrogate (~30 times faster per evaluation): the
  // Table 5.1 fit, with its own budget, gives one more start of the exact search, which
  // therefore ends no worse than the corrected method.
  // Under a time limit the surrogate's stages take at most a tenth of the time left each, and
  // the exact search starts from the surrogate's optimum (evaluated first) with the start as
  // the extra one.
  std::vector<double> exact_with_surrogate() {
    const bool timed = settings_.search.deadline.has_value();
    const std::vector<double> approximate = run(FitMethod::approximate, coordinates_.z0, total() / 2, {}, 0.1);
    std::vector<std::vector<double>> surrogate{approximate};
    if (!result_.interrupted) {
      corrections_ = corrections_at(coordinates_.network(approximate), data_, settings_.score.harmonic);
      surrogate = {run(FitMethod::corrected, approximate, total() - result_.evaluations, {}, 0.1)};
    }
    if (result_.interrupted) return surrogate.front();
    result_.time_limited = false;  // the surrogate's share ran out, not the fit's time
    if (timed) return run(FitMethod::exact, surrogate.front(), total(), {coordinates_.z0});
    return run(FitMethod::exact, coordinates_.z0, total(), surrogate);
  }

 private:
  int total() const { return settings_.search.max_evaluations; }

  const Coordinates& coordinates_;
  const std::vector<FitDataSet>& data_;
  const FitSettings& settings_;
  FitResult& result_;
  std::vector<ThesisCorrection> corrections_;
};

// Bugs of the caller: the front end and the CLI refuse these first, naming where.
void require_fittable(const Network& start, const std::vector<int>& free, const std::vector<FitDataSet>& data, const FitSettings& settings) {
  if (free.empty())
    throw std::logic_error(
        fmt::format("model '{}' has no free parameter; give bounds to the ones to fit, e.g. `k = 300 N/mm in [10, 5000]`", start.model().name));
  if (data.empty()) throw std::logic_error("a fit needs data: add `data \"FILE.csv\"` to the fit block or --data FILE.csv");
  if (settings.score.method != FitMethod::exact && std::any_of(data.begin(), data.end(), [](const FitDataSet& s) { return s.is_harmonic(); }))
    if (const std::string why = approximation_misfit(start); !why.empty())
      throw UsageError(fmt::format("cannot fit model '{}': {}", start.model().name, why));
  if (settings.score.method == FitMethod::approximate)  // the thesis's formulas (5.5-5.21) know no preload; `corrected` calibrates it in
    for (const FitDataSet& s : data)
      if (s.is_harmonic() && std::any_of(s.harmonic().preload.begin(), s.harmonic().preload.end(), [](double p) { return p != 0.0; }))
        throw UsageError(
            fmt::format("cannot fit {} with method = approximate: its points have a preload, which the thesis's approximation "
                        "(eqs. 5.5-5.21) does not know; use method = exact or corrected",
                        s.path));
}

}  // namespace

FitResult fit(const Network& start, const std::vector<int>& free, const std::vector<FitDataSet>& data, const FitSettings& given) {
  const auto clock_start = std::chrono::steady_clock::now();
  require_fittable(start, free, data, given);
  FitSettings settings = given;
  if (given.time_limit && *given.time_limit <= 1e8) {
    settings.search.deadline = clock_start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                 std::chrono::duration<double>(std::max(0.0, *given.time_limit)));
    // After the search: the standard errors' central differences (2 n + 1 evaluations) and the
    // final prediction of each data set, with half as much again for evaluations dearer than
    // the search's mean.
    const int after = (given.statistics ? 2 * static_cast<int>(free.size()) + 1 : 0) + static_cast<int>(data.size());
    settings.search.reserve_evaluations = (3 * after + 1) / 2;
  }
  std::vector<std::string> notes;
  std::vector<int> yeoh_started;
  const Network first = settings.yeoh_start_from_history ? start.with_parameters(yeoh_start(start, free, data, notes, yeoh_started)) : start;
  const Coordinates coordinates(first, free);
  const ScoreSettings& score = settings.score;
  settings.search.extra_starts.clear();
  for (const std::vector<double>& values : given.extra_starts) {
    if (values.size() != first.parameters().size())
      throw std::logic_error(fmt::format("fit: an extra start has {} values for {} parameters", values.size(), first.parameters().size()));
    std::vector<double> z = coordinates.z_of(values);
    for (std::size_t j = 0; j < z.size(); ++j)
      z[j] = std::isnan(z[j]) ? coordinates.z0[j] : std::clamp(z[j], coordinates.lower[j], coordinates.upper[j]);
    settings.search.extra_starts.push_back(std::move(z));
  }

  FitResult result{.network = start, .free = free, .start_values = first.parameters(), .yeoh_started = yeoh_started};
  result.notes = std::move(notes);
  for (const FitDataSet& set : data)
    if (set.is_harmonic()) {
      result.notes.insert(result.notes.end(), set.harmonic().notes.begin(), set.harmonic().notes.end());
      for (std::string& note : damping_left_out(set.harmonic())) result.notes.push_back(std::move(note));
    }

  StagedSearch searches(coordinates, data, settings, result);
  std::vector<double> z;
  FitMethod final_method = score.method;
  const std::vector<int> scales = score.method == FitMethod::exact && settings.separable && predictions_affine(first, data, score)
                                      ? force_scales(first, free)
                                      : std::vector<int>{};
  if (!scales.empty()) {
    z = searches.separable(scales);
    result.notes.push_back(
        fmt::format("{} of the {} free parameters solved exactly for every shape the search tried (force scales: the "
                    "model's force is linear in them)",
                    scales.size(), free.size()));
  } else if (score.method == FitMethod::corrected) z = searches.corrected(final_method);
  else if (score.method == FitMethod::exact && !settings.search.algorithm && approximation_applies(first, data))
    z = searches.exact_with_surrogate();
  else z = searches.run(score.method, coordinates.z0, settings.search.max_evaluations);

  result.network = coordinates.network(z);
  if (result.time_limited)
    result.notes.push_back(fmt::format("stopped at the time limit of {:g} s after {} evaluations: these are the best values found by then",
                                       *settings.time_limit, result.evaluations));
  StatisticsWithOffsets statistics;
  if (!result.interrupted && settings.statistics) {
    if (settings.sensitivities && residual_jacobian_applies(result.network, data, score, final_method)) {  // harmonic only: no offsets
      const ResidualsWithJacobian at = residual_jacobian(coordinates, z, data, score);
      if (at.jacobian.cols() > 0)
        statistics.parameters = parameter_statistics(
            Eigen::Map<const Eigen::VectorXd>(at.residuals.data(), static_cast<Eigen::Index>(at.residuals.size())), at.jacobian, z,
            coordinates.logarithmic);
    }
    if (statistics.parameters.residuals == 0)
      statistics = all_histories(data)  // a block of samples at a time (history_scoring.hpp)
                       ? history_statistics([&](const std::vector<double>& at) { return coordinates.network(at); }, data, score, z,
                                            coordinates.logarithmic)
                       : statistics_with_offsets(searches.predictions_for(final_method), data, score, z, coordinates.logarithmic);
    result.statistics = statistics.parameters;
    if (!result.statistics.has_noise_estimate())
      result.notes.push_back(
          fmt::format("no standard errors: {} residuals for {} identifiable directions leave no degree of freedom to "
                      "estimate the noise; add data points or fix parameters",
                      result.statistics.residuals, result.statistics.rank));
  }
  std::size_t harmonic_points = 0;
  for (const FitDataSet& set : data) {
    result.datasets.push_back(data_set_fit(result.network, set, score.harmonic));
    if (const std::size_t f = result.datasets.size() - 1; f < statistics.offsets.size() && set.force_offset.free)
      add_offset_statistics(result.datasets.back().force_offset, statistics.offsets[f]);
    if (set.is_harmonic()) {
      result.phi += result.datasets.back().phi;
      harmonic_points += set.harmonic().size();
    }
  }
  result.err = harmonic_points > 0 ? std::sqrt(result.phi) / static_cast<double>(harmonic_points) : 0.0;
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return result;
}

}  // namespace rheo::runtime
