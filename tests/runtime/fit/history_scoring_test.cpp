// The fits of histories scored a block of samples at a time (runtime/fit/history_scoring.hpp)
// against the whole-vector paths: the force scales against an Eigen dense bounded least-squares
// solve of the full design matrix (offsets eliminated by centring, not by a column), with and
// without a free or declared offset and with a bound active; the statistics against
// statistics_with_offsets (the full Jacobian and its SVD), with a free offset.
#include "runtime/fit/history_scoring.hpp"

#include "runtime/fit/bounded_least_squares.hpp"
#include "runtime/fit/fit.hpp"
#include "runtime/fit/fit_coordinates.hpp"
#include "runtime/protocols/run_history.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <string>

namespace history_scoring_test {

using namespace rheo;

namespace {

const char* kTruth = "model t { spring e (k = 100 N/mm) maxwell m (k = 50 N/mm, tau = 20 ms) }";

// The start: tau three times the truth's, so the scales cannot fit the data exactly.
std::string start_model(double e_upper) {
  return "model t { spring e (k = " + std::to_string(std::min(300.0, 0.75 * e_upper)) + " N/mm in [1, " + std::to_string(e_upper) +
         "]) maxwell m (k = 150 N/mm in [1, 10000], tau = 60 ms in [0.1, 10000]) }";
}

// The truth's history plus an offset of 150 N and a deterministic ripple (1 % of the force).
runtime::FitDataSet measured(runtime::ForceOffset offset) {
  runtime::FitDataSet set = test::history_data_of(test::network_from(kTruth, "t"), runtime::quasistatic_sine({1.0, 0.3}, 2.0, 2, 400), "rig.csv",
                                                  0.7, 150.0);
  auto& h = std::get<runtime::HistoryData>(set.data);
  for (std::size_t j = 0; j < h.force.size(); ++j) h.force[j] += 0.01 * h.force_scale * std::sin(0.37 * static_cast<double>(j));
  set.force_offset = offset;
  return set;
}

struct Dense {
  Eigen::VectorXd s;
  double objective = 0.0;
};

// The whole design matrix: A_k = w (F(s0 + s0_k e_k) - F(s0)) / s0_k, r0 = w (F(s0) + c - F_exp),
// both centred for a free offset; the bounded solve of min || A d + r0 ||.
Dense dense_solve(const runtime::Network& network, const std::vector<int>& scales, const std::vector<double>& lower,
                  const std::vector<double>& upper, const runtime::FitDataSet& set) {
  const auto& h = set.history();
  const auto m = static_cast<Eigen::Index>(h.force.size()), n = static_cast<Eigen::Index>(scales.size());
  const double w = std::sqrt(set.weight / static_cast<double>(m)) / h.force_scale;
  const auto force = [&](const std::vector<double>& values) {
    const std::vector<double> f = runtime::history_force(network.with_parameters(values), h.drive);
    return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(f.data(), m));
  };
  std::vector<double> values = network.parameters();
  Eigen::VectorXd s0(n);
  for (Eigen::Index k = 0; k < n; ++k) s0(k) = values[static_cast<std::size_t>(scales[static_cast<std::size_t>(k)])];
  const Eigen::VectorXd f0 = force(values);
  Eigen::MatrixXd a(m, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    std::vector<double> moved = values;
    moved[static_cast<std::size_t>(scales[static_cast<std::size_t>(k)])] = 2.0 * s0(k);
    a.col(k) = w * (force(moved) - f0) / s0(k);
  }
  const double declared = set.force_offset.given && !set.force_offset.free ? set.force_offset.value : 0.0;
  Eigen::VectorXd r0 = w * (f0.array() + declared - Eigen::Map<const Eigen::VectorXd>(h.force.data(), m).array()).matrix();
  if (set.force_offset.free) {
    r0.array() -= r0.mean();
    for (Eigen::Index k = 0; k < n; ++k) a.col(k).array() -= a.col(k).mean();
  }
  const Eigen::VectorXd lo = Eigen::Map<const Eigen::VectorXd>(lower.data(), n), hi = Eigen::Map<const Eigen::VectorXd>(upper.data(), n);
  const Eigen::VectorXd d = runtime::bounded_least_squares(a, -r0, lo - s0, hi - s0).x;
  return {s0 + d, (a * d + r0).squaredNorm()};
}

}  // namespace

TEST_CASE("streamed scale solve: the dense bounded least squares of the whole design matrix, offsets free, declared or none, a bound active") {
  struct Case {
    const char* name;
    runtime::ForceOffset offset;
    double e_upper;
  };
  for (const Case& c : {Case{"free offset", {.given = true, .free = true}, 10000.0},
                        Case{"declared offset", {.given = true, .free = false, .value = 150.0}, 10000.0}, Case{"no offset", {}, 10000.0},
                        Case{"free offset, e.k held at its bound", {.given = true, .free = true}, 40.0}}) {
    CAPTURE(c.name);
    const runtime::Network start = test::network_from(start_model(c.e_upper), "t");
    const std::vector<int> scales{test::parameter_index(start, "e.k"), test::parameter_index(start, "m.k")};
    const std::vector<double> lower{1.0, 1.0}, upper{c.e_upper, 10000.0};
    const std::vector<runtime::FitDataSet> data{measured(c.offset)};
    runtime::ScoreSettings score;
    const runtime::ScaleSolution streamed = runtime::solve_history_scales(start, scales, lower, upper, data, score);
    const Dense dense = dense_solve(start, scales, lower, upper, data.front());
    for (std::size_t k = 0; k < scales.size(); ++k)
      CHECK(test::relative_error(streamed.values[static_cast<std::size_t>(scales[k])], dense.s(static_cast<Eigen::Index>(k))) < 1e-11);
    CHECK(test::relative_error(streamed.objective, dense.objective) < 1e-10);
    CHECK(dense.objective > 1e-6);  // the ripple and the wrong tau: a residual to agree on
    CHECK(streamed.evaluations == 3);
    if (c.e_upper < 100.0) CHECK(streamed.values[static_cast<std::size_t>(scales[0])] == c.e_upper);
  }
}

TEST_CASE("streamed statistics: the standard errors and correlations of the full Jacobian's, a free offset among them") {
  const runtime::Network start = test::network_from(start_model(10000.0), "t");
  const std::vector<runtime::FitDataSet> data{measured({.given = true, .free = true})};
  const std::vector<int> free = runtime::bounded_parameters(start);
  const runtime::Coordinates coordinates(start, free);
  runtime::ScoreSettings score;
  const auto network_at = [&](const std::vector<double>& z) { return coordinates.network(z); };
  const auto predictions = [&](const std::vector<double>& z) {
    return std::vector<runtime::Prediction>{
        runtime::predict(coordinates.network(z), data.front(), runtime::FitMethod::exact, score.harmonic, nullptr, runtime::Offsets::declared)};
  };
  const runtime::StatisticsWithOffsets streamed = runtime::history_statistics(network_at, data, score, coordinates.z0, coordinates.logarithmic);
  const runtime::StatisticsWithOffsets whole = runtime::statistics_with_offsets(predictions, data, score, coordinates.z0, coordinates.logarithmic);
  REQUIRE(streamed.parameters.standard_error.size() == free.size());
  CHECK(streamed.parameters.rank == whole.parameters.rank);
  CHECK(streamed.parameters.residuals == whole.parameters.residuals);
  for (std::size_t i = 0; i < free.size(); ++i) {
    CAPTURE(i);
    CHECK(streamed.parameters.identifiable[i] == whole.parameters.identifiable[i]);
    CHECK(test::relative_error(streamed.parameters.standard_error[i], whole.parameters.standard_error[i]) < 1e-9);
    for (std::size_t j = 0; j < free.size(); ++j)
      if (i != j) CHECK(std::abs(streamed.parameters.correlation[i][j] - whole.parameters.correlation[i][j]) < 1e-9);
  }
  const runtime::FittedOffset &o = streamed.offsets.front(), &w = whole.offsets.front();
  CHECK(test::relative_error(o.standard_error, w.standard_error) < 1e-9);
  REQUIRE(o.correlation.size() == w.correlation.size());
  for (std::size_t j = 0; j < o.correlation.size(); ++j) CHECK(std::abs(o.correlation[j] - w.correlation[j]) < 1e-9);
}

}  // namespace history_scoring_test
