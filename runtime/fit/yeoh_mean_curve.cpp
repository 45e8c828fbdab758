#include "runtime/fit/yeoh_mean_curve.hpp"

#include "runtime/core/errors.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>

namespace rheo::runtime {
namespace {

constexpr double kReachTolerance = 1e-3;   // of the range: a run "reaches" an extreme
constexpr double kMergeTolerance = 1e-12;  // of the range: displacements that coincide

struct Run {
  std::size_t first, last;  // inclusive sample indices
  int direction;            // +1 non-decreasing, -1 non-increasing
};

std::vector<Run> monotone_runs(const std::vector<double>& u) {
  std::vector<Run> runs;
  std::size_t start = 0;
  int direction = 0;
  for (std::size_t k = 1; k < u.size(); ++k) {
    const int s = (u[k] > u[k - 1]) - (u[k] < u[k - 1]);
    if (s == 0) continue;
    if (direction == 0) {
      direction = s;
    } else if (s != direction) {
      runs.push_back({start, k - 1, direction});
      start = k - 1;
      direction = s;
    }
  }
  if (direction != 0) runs.push_back({start, u.size() - 1, direction});
  return runs;
}

using Branch = std::vector<std::pair<double, double>>;  // (u, F), sorted by u, u unique

void append(const LoopSamples& loop, std::size_t first, std::size_t last, Branch& branch) {
  for (std::size_t k = first; k <= last; ++k) branch.emplace_back(loop.displacement[k], loop.force[k]);
}

Branch sorted_single_valued(Branch branch) {
  std::stable_sort(branch.begin(), branch.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  Branch out;
  for (std::size_t i = 0; i < branch.size();) {
    std::size_t j = i;
    double sum = 0.0;
    while (j < branch.size() && branch[j].first == branch[i].first) sum += branch[j++].second;
    out.emplace_back(branch[i].first, sum / static_cast<double>(j - i));
    i = j;
  }
  return out;
}

// The branch of the given direction per step 2 of the header, or nullopt.
std::optional<Branch> full_branch(const LoopSamples& loop, const std::vector<Run>& runs, int direction, double u_min, double u_max) {
  const double reach = kReachTolerance * (u_max - u_min);
  auto covers = [&](double lo, double hi) { return lo <= u_min + reach && hi >= u_max - reach; };
  auto extent = [&](const Run& r) {
    const auto [lo, hi] = std::minmax(loop.displacement[r.first], loop.displacement[r.last]);
    return std::pair{lo, hi};
  };
  for (auto r = runs.rbegin(); r != runs.rend(); ++r) {
    if (r->direction != direction) continue;
    const auto [lo, hi] = extent(*r);
    if (!covers(lo, hi)) continue;
    Branch b;
    append(loop, r->first, r->last, b);
    return sorted_single_valued(std::move(b));
  }
  // Periodic join of the last and the first run (a record that starts and ends mid-branch).
  const auto& u = loop.displacement;
  if (runs.size() < 2 || runs.front().direction != direction || runs.back().direction != direction) return std::nullopt;
  if (std::abs(u.back() - u.front()) > reach) return std::nullopt;
  const auto [lo1, hi1] = extent(runs.back());
  const auto [lo2, hi2] = extent(runs.front());
  if (!covers(std::min(lo1, lo2), std::max(hi1, hi2))) return std::nullopt;
  Branch b;
  append(loop, runs.back().first, runs.back().last, b);
  append(loop, runs.front().first + 1, runs.front().last, b);
  return sorted_single_valued(std::move(b));
}

// Linear interpolation in a sorted branch; x within its range.
double interpolate(const Branch& b, double x) {
  auto hi = std::lower_bound(b.begin(), b.end(), x, [](const auto& p, double v) { return p.first < v; });
  if (hi == b.end()) return b.back().second;
  if (hi->first == x || hi == b.begin()) return hi->second;
  const auto lo = hi - 1;
  const double w = (x - lo->first) / (hi->first - lo->first);
  return lo->second + w * (hi->second - lo->second);
}

void check_sizes(const LoopSamples& s, const char* what) {
  if (s.displacement.size() != s.force.size())
    throw std::logic_error(fmt::format("{}: {} displacements but {} forces", what, s.displacement.size(), s.force.size()));
}

}  // namespace

LoopSamples loop_samples_from_table(const Table& table) {
  const int u = table.column("displacement"), f = table.column("force");
  if (u < 0 || f < 0)
    throw DataError(
        fmt::format("{}a loop needs the columns 'displacement' and 'force' (with units, e.g. "
                    "'displacement [mm]'); the table has no '{}' column ({})",
                    header_error(table), u < 0 ? "displacement" : "force", header_columns(table)));
  return {table.columns[static_cast<std::size_t>(u)], table.columns[static_cast<std::size_t>(f)]};
}

LoopSamples largest_loop(const LoopSamples& history) {
  check_sizes(history, "largest_loop");
  const auto [a, b] = largest_cycle(history.displacement);
  LoopSamples loop;
  loop.displacement.assign(history.displacement.begin() + static_cast<std::ptrdiff_t>(a),
                           history.displacement.begin() + static_cast<std::ptrdiff_t>(b) + 1);
  loop.force.assign(history.force.begin() + static_cast<std::ptrdiff_t>(a), history.force.begin() + static_cast<std::ptrdiff_t>(b) + 1);
  return loop;
}

std::pair<std::size_t, std::size_t> largest_cycle(const std::vector<double>& u) {
  if (u.size() < 3) throw DataError("largest_loop: the record has fewer than 3 samples");
  const auto [lo_it, hi_it] = std::minmax_element(u.begin(), u.end());
  const double level = 0.5 * (*lo_it + *hi_it), range = *hi_it - *lo_it;
  std::vector<std::size_t> starts;
  for (std::size_t k = 0; k + 1 < u.size(); ++k)
    if (u[k] <= level && u[k + 1] > level) starts.push_back(k);
  std::vector<std::pair<std::size_t, std::size_t>> cycles;
  for (std::size_t i = 0; i + 1 < starts.size(); ++i) cycles.emplace_back(starts[i], starts[i + 1]);
  if (!starts.empty() && starts.back() + 1 < u.size() && std::abs(u.back() - level) <= 1e-6 * range)
    cycles.emplace_back(starts.back(), u.size() - 1);
  if (cycles.empty() || !(range > 0.0))
    throw DataError("largest_loop: the record holds no full cycle (an upward crossing of the mid level followed by another)");
  std::vector<double> amplitude;
  for (const auto& [a, b] : cycles) {
    const auto [lo, hi] = std::minmax_element(u.begin() + static_cast<std::ptrdiff_t>(a), u.begin() + static_cast<std::ptrdiff_t>(b) + 1);
    amplitude.push_back(0.5 * (*hi - *lo));
  }
  const double largest = *std::max_element(amplitude.begin(), amplitude.end());
  std::size_t chosen = 0;
  for (std::size_t i = 0; i < cycles.size(); ++i)
    if (amplitude[i] >= (1.0 - 1e-3) * largest) chosen = i;
  return cycles[chosen];
}

MeanCurve mean_curve(const LoopSamples& loop, double turning_margin) {
  check_sizes(loop, "mean_curve");
  if (!(turning_margin >= 0.0 && turning_margin < 0.5))
    throw std::logic_error(fmt::format("mean_curve: turning margin {} is outside [0, 0.5)", turning_margin));
  if (loop.displacement.size() < 3) throw DataError("the loop has fewer than 3 samples");
  const auto [lo_it, hi_it] = std::minmax_element(loop.displacement.begin(), loop.displacement.end());
  const double u_min = *lo_it, u_max = *hi_it, range = u_max - u_min;
  const auto runs = monotone_runs(loop.displacement);
  const auto loading = full_branch(loop, runs, +1, u_min, u_max);
  const auto unloading = full_branch(loop, runs, -1, u_min, u_max);
  if (!loading || !unloading)
    throw DataError(fmt::format("its widest loop has no full {} branch from {} mm to {} mm; a yeoh start needs at least one closed cycle",
                                loading ? "unloading" : "loading", u_min, u_max));

  const double lo = std::max({loading->front().first, unloading->front().first, u_min + turning_margin * range});
  const double hi = std::min({loading->back().first, unloading->back().first, u_max - turning_margin * range});
  std::vector<double> grid;
  for (const Branch* b : {&*loading, &*unloading})
    for (const auto& [x, f] : *b)
      if (x >= lo && x <= hi) grid.push_back(x);
  std::sort(grid.begin(), grid.end());
  MeanCurve curve;
  for (double x : grid) {
    if (!curve.displacement.empty() && x - curve.displacement.back() <= kMergeTolerance * range) continue;
    curve.displacement.push_back(x);
    curve.force.push_back(0.5 * (interpolate(*loading, x) + interpolate(*unloading, x)));
  }
  if (curve.displacement.size() < 3)
    throw DataError(
        fmt::format("only {} common displacements remain between {} mm and {} mm after excluding "
                    "the turning regions; sample the loop more densely or reduce the margin",
                    curve.displacement.size(), lo, hi));
  return curve;
}

YeohConstants fit_yeoh_least_squares(const MeanCurve& curve) {
  const std::size_t m = curve.displacement.size();
  if (m < 3 || curve.force.size() != m)
    throw std::logic_error(fmt::format("fit_yeoh_least_squares: need at least 3 (u, F) pairs of equal count, got {} and {}", m, curve.force.size()));
  Eigen::MatrixXd a(static_cast<Eigen::Index>(m), 3);
  Eigen::VectorXd f(static_cast<Eigen::Index>(m));
  for (std::size_t i = 0; i < m; ++i) {
    const double u = curve.displacement[i], u2 = u * u;
    const auto r = static_cast<Eigen::Index>(i);
    a(r, 0) = 2.0 * u;  // (5.28)
    a(r, 1) = 4.0 * u * u2;
    a(r, 2) = 6.0 * u * u2 * u2;
    f(r) = curve.force[i];
  }
  const Eigen::Vector3d scale = a.colwise().norm().transpose();
  if ((scale.array() == 0.0).any()) throw NumericalError("fit_yeoh_least_squares: every displacement of the mean curve is 0");
  for (Eigen::Index j = 0; j < 3; ++j) a.col(j) /= scale(j);
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  if (qr.rank() < 3)
    throw NumericalError(
        fmt::format("fit_yeoh_least_squares: the {} displacements of the mean curve do not determine "
                    "three constants (rank {})",
                    m, qr.rank()));
  const Eigen::Vector3d d = qr.solve(f).cwiseQuotient(scale);  // (5.32) without forming A^T A
  return {d(0), d(1), d(2)};
}

YeohConstants yeoh_from_shape(const YeohConstants& least_squares, double elastic_stiffness) {
  if (!(elastic_stiffness > 0.0)) throw std::logic_error(fmt::format("yeoh_from_shape: need K_e > 0, got {}", elastic_stiffness));
  if (least_squares.d10 == 0.0)
    throw NumericalError("yeoh_from_shape: the least-squares D10 is 0, so the shape ratios D20/D10 and D30/D10 (eq. 5.33) are undefined");
  const double a = least_squares.d20 / least_squares.d10, b = least_squares.d30 / least_squares.d10;  // (5.33)
  const double d10 = 0.5 * elastic_stiffness;                                                         // (5.35)
  return {d10, a * d10, b * d10};                                                                     // (5.36)
}

std::array<YeohStartValue, 3> yeoh_start_values(const lang::CheckedModel& model, const std::array<int, 3>& yeoh, const std::vector<int>& free,
                                                const LoopSamples& record) {
  return yeoh_start_values_of_loop(model, yeoh, free, largest_loop(record));
}

std::array<YeohStartValue, 3> yeoh_start_values_of_loop(const lang::CheckedModel& model, const std::array<int, 3>& yeoh,
                                                        const std::vector<int>& free, const LoopSamples& loop) {
  const YeohConstants d = fit_yeoh_least_squares(mean_curve(loop));
  const double constants[] = {d.d10, d.d20, d.d30};
  std::array<YeohStartValue, 3> out;
  for (std::size_t slot = 0; slot < 3; ++slot) {
    const lang::Parameter& p = model.parameters.at(static_cast<std::size_t>(yeoh[slot]));
    out[slot] = {yeoh[slot], p.free ? std::clamp(constants[slot], p.lower, p.upper) : constants[slot], constants[slot],
                 std::find(free.begin(), free.end(), yeoh[slot]) != free.end()};
  }
  return out;
}

}  // namespace rheo::runtime
