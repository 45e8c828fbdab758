#include "runtime/fit/history_scoring.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/fit/bounded_least_squares.hpp"
#include "runtime/fit/fit_statistics.hpp"
#include "runtime/fit/history_blocks.hpp"
#include "runtime/fit/streaming_least_squares.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rheo::runtime {
using history_blocks::for_each_block;
using history_blocks::free_offset;
using history_blocks::residual_scale;

bool all_histories(const std::vector<FitDataSet>& data) {
  return !data.empty() && std::none_of(data.begin(), data.end(), [](const FitDataSet& set) { return set.is_harmonic(); });
}

ScaleSolution solve_history_scales(const Network& network, const std::vector<int>& scales, const std::vector<double>& lower,
                                   const std::vector<double>& upper, const std::vector<FitDataSet>& data, const ScoreSettings& score) {
  if (scales.size() != lower.size() || scales.size() != upper.size() || !all_histories(data))
    throw std::logic_error("solve_history_scales: one lower and one upper bound per scale, and histories only");
  const auto ns = static_cast<Eigen::Index>(scales.size());
  std::vector<double> values = network.parameters();
  Eigen::VectorXd s0(ns), h(ns);
  for (Eigen::Index j = 0; j < ns; ++j) {
    const auto u = static_cast<std::size_t>(j);
    double& s = values[static_cast<std::size_t>(scales[u])];
    s = std::clamp(s, lower[u], upper[u]);
    s0(j) = s;
  }
  std::vector<Network> networks{network.with_parameters(values)};
  for (Eigen::Index j = 0; j < ns; ++j) {
    const auto u = static_cast<std::size_t>(j);
    double& s = values[static_cast<std::size_t>(scales[u])];
    // As separable_fit.cpp steps: half the value (the sign kept) or a thousandth of the range.
    const double step = std::max(0.5 * std::abs(s), 1e-3 * (std::isfinite(upper[u] - lower[u]) ? upper[u] - lower[u] : 1.0));
    h(j) = s + step <= upper[u] ? step : -step;
    s += h(j);
    networks.push_back(network.with_parameters(values));
    s = s0(j);
  }
  std::vector<Eigen::Index> offset_column(data.size(), -1);
  Eigen::Index offsets = 0;
  for (std::size_t f = 0; f < data.size(); ++f)
    if (free_offset(data[f])) offset_column[f] = offsets++;

  StreamingLeastSquares rows(offsets + ns);
  for (std::size_t f = 0; f < data.size(); ++f) {
    const HistoryData& measured = data[f].history();
    const double scale = residual_scale(data[f]), declared = force_offset(data[f], {}, Offsets::declared);
    for_each_block(
        networks, measured, score.harmonic.solver, score.harmonic.threads, [&](std::size_t first, std::size_t count, const Eigen::MatrixXd& forces) {
          if (!forces.topRows(static_cast<Eigen::Index>(count)).allFinite())
            throw NumericalError("the model's response at these parameters is not finite (NaN or infinite force); its scales cannot be solved");
          for (std::size_t i = 0; i < count; ++i) {
            const auto ii = static_cast<Eigen::Index>(i);
            double* row = rows.next_row();
            if (offset_column[f] >= 0) row[offset_column[f]] = scale;
            const double f0 = forces(ii, 0);
            for (Eigen::Index k = 0; k < ns; ++k) row[offsets + k] = scale * ((forces(ii, k + 1) - f0) / h(k));
            row[offsets + ns] = -scale * (f0 + declared - measured.force[first + i]);
          }
        });
  }
  const Eigen::MatrixXd r = rows.r();
  const Eigen::VectorXd c = rows.c();
  const double rest = rows.rest();
  if (!r.allFinite() || !c.allFinite() || !std::isfinite(rest))
    throw NumericalError("the residuals of the model's response are not finite; its scales cannot be solved");
  const Eigen::MatrixXd r_scales = r.bottomRightCorner(ns, ns);
  const Eigen::VectorXd c_scales = c.tail(ns);
  const Eigen::VectorXd lo = Eigen::Map<const Eigen::VectorXd>(lower.data(), ns), hi = Eigen::Map<const Eigen::VectorXd>(upper.data(), ns);
  const Eigen::VectorXd s = (s0 + bounded_least_squares(r_scales, c_scales, lo - s0, hi - s0).x).cwiseMax(lo).cwiseMin(hi);

  ScaleSolution out;
  out.values = network.parameters();
  for (Eigen::Index j = 0; j < ns; ++j) out.values[static_cast<std::size_t>(scales[static_cast<std::size_t>(j)])] = s(j);
  out.objective = (r_scales * (s - s0) - c_scales).squaredNorm() + rest * rest;
  out.evaluations = static_cast<int>(ns) + 1;
  return out;
}

StatisticsWithOffsets history_statistics(const std::function<Network(const std::vector<double>&)>& network_at, const std::vector<FitDataSet>& data,
                                         const ScoreSettings& score, const std::vector<double>& z, const std::vector<bool>& logarithmic) {
  if (!all_histories(data)) throw std::logic_error("history_statistics: histories only");
  const std::size_t n = z.size();
  const SolverChoice solver = score.harmonic.solver;
  std::vector<Network> networks{network_at(z)};
  std::vector<double> x = z;  // the coordinates: z, then each free offset at its optimum
  std::vector<bool> log_x = logarithmic;
  std::vector<std::size_t> free_sets;
  for (std::size_t f = 0; f < data.size(); ++f) {
    if (!free_offset(data[f])) continue;
    // force_offset's mean, in its order of operations: sum (F_exp - F), then / M.
    const HistoryData& measured = data[f].history();
    double sum = 0.0;
    for_each_block({networks.front()}, measured, solver, score.harmonic.threads,
                   [&](std::size_t first, std::size_t count, const Eigen::MatrixXd& forces) {
                     for (std::size_t i = 0; i < count; ++i) sum += measured.force[first + i] - (forces(static_cast<Eigen::Index>(i), 0) + 0.0);
                   });
    free_sets.push_back(f);
    x.push_back(sum / static_cast<double>(measured.force.size()));
    log_x.push_back(false);
  }
  // fit_statistics.hpp's central differences: x_j +- h_j, divided by the difference of the two.
  std::vector<double> width(x.size()), up(x.size()), down(x.size());
  for (std::size_t j = 0; j < x.size(); ++j) {
    const double h = kStatisticsRelativeStep * std::max(1.0, std::abs(x[j]));
    up[j] = x[j] + h, down[j] = x[j] - h, width[j] = up[j] - down[j];
  }
  std::vector<double> shifted = z;
  for (std::size_t j = 0; j < n; ++j) {
    for (const double at : {up[j], down[j]}) {
      shifted[j] = at;
      networks.push_back(network_at(shifted));
    }
    shifted[j] = z[j];
  }

  const auto columns = static_cast<Eigen::Index>(x.size());
  StreamingLeastSquares rows(columns);
  double squared_norm = 0.0;
  for (std::size_t f = 0; f < data.size(); ++f) {
    const HistoryData& measured = data[f].history();
    const double scale = residual_scale(data[f]), declared = force_offset(data[f], {}, Offsets::declared);
    const auto k = static_cast<std::size_t>(std::find(free_sets.begin(), free_sets.end(), f) - free_sets.begin());
    const double offset = k < free_sets.size() ? x[n + k] : 0.0;
    // statistics_with_offsets's residual: s ((F + declared) + c - F_exp), c where the offset is free.
    const auto residual = [&](double force, double c, double f_exp) {
      const double with_offsets = k < free_sets.size() ? force + declared + c : force + declared;
      return scale * (with_offsets - f_exp);
    };
    for_each_block(networks, measured, solver, score.harmonic.threads, [&](std::size_t first, std::size_t count, const Eigen::MatrixXd& forces) {
      for (std::size_t i = 0; i < count; ++i) {
        const auto ii = static_cast<Eigen::Index>(i);
        const double f_exp = measured.force[first + i];
        const double r0 = residual(forces(ii, 0), offset, f_exp);
        double* row = rows.next_row();
        for (std::size_t j = 0; j < n; ++j) {
          const auto jj = static_cast<Eigen::Index>(j);
          row[j] = (residual(forces(ii, 1 + 2 * jj), offset, f_exp) - residual(forces(ii, 2 + 2 * jj), offset, f_exp)) / width[j];
        }
        if (k < free_sets.size())
          row[n + k] = (residual(forces(ii, 0), up[n + k], f_exp) - residual(forces(ii, 0), down[n + k], f_exp)) / width[n + k];
        row[columns] = r0;
        if (!std::isfinite(r0) || !std::all_of(row, row + columns, [](double v) { return std::isfinite(v); }))
          throw NumericalError(kStatisticsNotFinite);
        squared_norm += r0 * r0;
      }
    });
  }
  const ParameterStatistics all = parameter_statistics_of_factor(rows.r(), squared_norm, rows.rows(), x, log_x);
  return split_offsets(all, n, free_sets, data.size());
}

}  // namespace rheo::runtime
