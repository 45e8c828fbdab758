#include "runtime/fit/history_jacobian.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/fit/force_offset.hpp"
#include "runtime/fit/history_blocks.hpp"
#include "runtime/fit/streaming_least_squares.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rheo::runtime {
namespace {

using history_blocks::for_each_block;
using history_blocks::free_offset;
using history_blocks::residual_scale;

// The sum of squares of d_1..d_M, also about their mean, accumulated by Welford's update (no
// cancellation where the mean is large against the spread).
struct RunningSquares {
  double count = 0.0, mean = 0.0, about_mean = 0.0;
  void add(double d) {
    count += 1.0;
    const double delta = d - mean;
    mean += delta / count;
    about_mean += delta * (d - mean);
  }
  double sum_of_squares(bool mean_removed) const { return mean_removed ? about_mean : about_mean + count * mean * mean; }
};

}  // namespace

std::optional<ReducedHistoryJacobian> reduced_history_jacobian(const std::function<Network(const std::vector<double>&)>& network_at,
                                                               const std::vector<FitDataSet>& data, const ScoreSettings& score,
                                                               const std::vector<double>& z, const std::vector<double>& steps) {
  if (steps.size() != z.size() || data.empty() || std::any_of(data.begin(), data.end(), [](const FitDataSet& set) { return set.is_harmonic(); }))
    throw std::logic_error("reduced_history_jacobian: one step per coordinate, and histories only");
  const auto n = static_cast<Eigen::Index>(z.size());
  std::vector<Eigen::Index> moved_column;  // network k + 1 is moved along this coordinate
  try {
    std::vector<Network> networks{network_at(z)};
    std::vector<double> moved = z;
    for (Eigen::Index k = 0; k < n; ++k) {
      const auto u = static_cast<std::size_t>(k);
      if (steps[u] == 0.0) continue;
      moved[u] = z[u] + steps[u];
      networks.push_back(network_at(moved));
      moved[u] = z[u];
      moved_column.push_back(k);
    }
    std::vector<Eigen::Index> offset_column(data.size(), -1);
    Eigen::Index offsets = 0;
    for (std::size_t f = 0; f < data.size(); ++f)
      if (free_offset(data[f])) offset_column[f] = offsets++;

    StreamingLeastSquares rows(offsets + n);
    std::vector<RunningSquares> squares(moved_column.size());
    std::vector<double> phi(moved_column.size(), 0.0);
    bool finite = true;
    for (std::size_t f = 0; f < data.size() && finite; ++f) {
      const HistoryData& measured = data[f].history();
      const double scale = residual_scale(data[f]), declared = force_offset(data[f], {}, Offsets::declared);
      std::fill(squares.begin(), squares.end(), RunningSquares{});
      for_each_block(networks, measured, score.harmonic.solver, score.harmonic.threads,
                     [&](std::size_t first, std::size_t count, const Eigen::MatrixXd& forces) {
                       if (!finite || !forces.topRows(static_cast<Eigen::Index>(count)).allFinite()) {
                         finite = false;
                         return;
                       }
                       for (std::size_t i = 0; i < count; ++i) {
                         const auto ii = static_cast<Eigen::Index>(i);
                         const double f_exp = measured.force[first + i], f0 = forces(ii, 0);
                         double* row = rows.next_row();
                         if (offset_column[f] >= 0) row[offset_column[f]] = scale;
                         for (std::size_t m = 0; m < moved_column.size(); ++m) {
                           const Eigen::Index k = moved_column[m];
                           const double fk = forces(ii, static_cast<Eigen::Index>(m) + 1);
                           row[offsets + k] = scale * ((fk - f0) / steps[static_cast<std::size_t>(k)]);
                           squares[m].add(scale * (fk + declared - f_exp));
                         }
                         row[offsets + n] = -scale * (f0 + declared - f_exp);
                       }
                     });
      for (std::size_t m = 0; m < squares.size(); ++m) phi[m] += squares[m].sum_of_squares(offset_column[f] >= 0);
    }
    if (!finite) return std::nullopt;
    ReducedHistoryJacobian out;
    out.r = rows.r().bottomRightCorner(n, n);
    out.c = -rows.c().tail(n);
    if (!out.r.allFinite() || !out.c.allFinite()) return std::nullopt;
    out.moved_values.assign(z.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t m = 0; m < moved_column.size(); ++m) out.moved_values[static_cast<std::size_t>(moved_column[m])] = phi[m];
    return out;
  } catch (const NumericalError&) {
    return std::nullopt;
  }
}

double history_phi(const Network& network, const std::vector<FitDataSet>& data, const ScoreSettings& score) {
  const std::vector<Network> networks{network};
  double phi = 0.0;
  for (const FitDataSet& set : data) {
    const HistoryData& measured = set.history();
    const double scale = residual_scale(set), declared = force_offset(set, {}, Offsets::declared);
    RunningSquares squares;
    for_each_block(networks, measured, score.harmonic.solver, 1, [&](std::size_t first, std::size_t count, const Eigen::MatrixXd& forces) {
      for (std::size_t i = 0; i < count; ++i) squares.add(scale * (forces(static_cast<Eigen::Index>(i), 0) + declared - measured.force[first + i]));
    });
    phi += squares.sum_of_squares(free_offset(set));
  }
  if (!std::isfinite(phi)) throw NumericalError("the model's response at these parameters is not finite (NaN or infinite force)");
  return phi;
}

std::size_t history_residual_count(const std::vector<FitDataSet>& data) {
  std::size_t m = 0;
  for (const FitDataSet& set : data) m += set.history().force.size();
  return m;
}

}  // namespace rheo::runtime
