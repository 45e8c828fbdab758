// The differenced Jacobian of history residuals reduced while the samples stream past
// (runtime/fit/history_jacobian.hpp) against the whole one: the residual vectors of
// fit_scoring.hpp at the base and the moved points, differenced into an m x n matrix. The
// reduced form must give the whole form's linear model (R^T R = J^T J, R^T c = J^T r,
// ||c|| <= ||r||), hence its damped steps, and the moved points' phi; and a fit taking it must
// reach the minimum the whole-vector fit reaches.
#include "runtime/fit/history_jacobian.hpp"

#include "runtime/fit/damped_step.hpp"
#include "runtime/fit/fit.hpp"
#include "runtime/fit/fit_coordinates.hpp"
#include "runtime/protocols/run_history.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>

#include <cmath>
#include <string>
#include <vector>

namespace history_jacobian_test {

using namespace rheo;

namespace {

const char* kTruth = "model t { spring e (k = 100 N/mm) maxwell m (k = 50 N/mm, tau = 20 ms) friction f (k = 80 N/mm, fy = 12 N) }";
const char* kStart =
    "model t { spring e (k = 100 N/mm) maxwell m (k = 50 N/mm, tau = 60 ms in [0.1, 10000]) friction f (k = 80 N/mm, fy = 30 N in [0.1, 1000]) }";

// Two files of the truth's loops, each with a deterministic ripple (1 % of its force) and a
// load cell's zero of 150 N: one states it, the other leaves it free (or states none).
std::vector<runtime::FitDataSet> measured(runtime::ForceOffset second) {
  const runtime::Network truth = test::network_from(kTruth, "t");
  std::vector<runtime::FitDataSet> data{test::history_data_of(truth, runtime::quasistatic_sine({1.0, 0.3}, 2.0, 2, 400), "slow.csv", 0.7, 150.0),
                                        test::history_data_of(truth, runtime::quasistatic_sine({0.6}, 11.0, 3, 300), "fast.csv", 1.3, 150.0)};
  data[0].force_offset = {.given = true, .free = false, .value = 150.0};
  data[1].force_offset = second;
  for (runtime::FitDataSet& set : data) {
    auto& h = std::get<runtime::HistoryData>(set.data);
    for (std::size_t j = 0; j < h.force.size(); ++j) h.force[j] += 0.01 * h.force_scale * std::sin(0.37 * static_cast<double>(j));
  }
  return data;
}

Eigen::VectorXd residuals(const runtime::Network& network, const std::vector<runtime::FitDataSet>& data, const runtime::ScoreSettings& score) {
  std::vector<double> r;
  for (const runtime::FitDataSet& set : data)
    runtime::append_residuals(set, runtime::predict(network, set, runtime::FitMethod::exact, score.harmonic, nullptr), score, r);
  return Eigen::Map<const Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size()));
}

}  // namespace

TEST_CASE("reduced history Jacobian: the whole Jacobian's linear model, damped steps and moved phi, with a free, declared or no offset") {
  struct Case {
    std::string name;
    runtime::ForceOffset second;
  };
  for (const Case& c : {Case{"free offset", {.given = true, .free = true}}, Case{"declared offset", {.given = true, .free = false, .value = 150.0}},
                        Case{"no offset", {}}}) {
    CAPTURE(c.name);
    const runtime::Network start = test::network_from(kStart, "t");
    const std::vector<int> free = runtime::bounded_parameters(start);
    const runtime::Coordinates coordinates(start, free);
    const std::vector<runtime::FitDataSet> data = measured(c.second);
    runtime::ScoreSettings score;
    const std::vector<double> z = coordinates.z0;
    // Forward, backward and no step (a coordinate that cannot move).
    const std::vector<double> steps{1e-6, -2e-6};
    const Eigen::VectorXd r = residuals(coordinates.network(z), data, score);
    Eigen::MatrixXd j(r.size(), 2);
    std::vector<double> moved_phi;
    for (std::size_t k = 0; k < steps.size(); ++k) {
      std::vector<double> moved = z;
      moved[k] += steps[k];
      const Eigen::VectorXd rk = residuals(coordinates.network(moved), data, score);
      j.col(static_cast<Eigen::Index>(k)) = (rk - r) / steps[k];
      moved_phi.push_back(rk.squaredNorm());
    }
    const auto reduced = runtime::reduced_history_jacobian([&](const std::vector<double>& at) { return coordinates.network(at); }, data, score, z,
                                                           steps);
    REQUIRE(reduced);
    const double size = (j.transpose() * j).norm();
    CHECK((reduced->r.transpose() * reduced->r - j.transpose() * j).norm() < 1e-10 * size);
    CHECK((reduced->r.transpose() * reduced->c - j.transpose() * r).norm() < 1e-10 * j.norm() * r.norm());
    CHECK(reduced->c.squaredNorm() <= r.squaredNorm() * (1.0 + 1e-12));
    CHECK(r.squaredNorm() - reduced->c.squaredNorm() > 1e-3 * r.squaredNorm());  // a residual the model does not reach: the test has teeth
    for (std::size_t k = 0; k < steps.size(); ++k) CHECK(test::relative_error(reduced->moved_values[k], moved_phi[k]) < 1e-10);
    // The damped steps of both forms, one damped and the undamped, a bound active.
    const runtime::DampedSteps whole(j, r), small(reduced->r, reduced->c);
    const Eigen::VectorXd scale = j.colwise().norm().transpose();
    // The two forms difference the same forces in another order (scaled, offset and centred
    // before or after), so their columns differ by the differencing's rounding, about eps / h
    // relative (2e-10 at h = 1e-6), and J is well conditioned here (cond about 5): the steps
    // agree to a hundred times that; a wrong scale, sign or offset column moves them by O(1).
    const double step_tolerance = 100.0 * 2.2e-16 / 1e-6;
    for (const double lambda : {1e-2, 0.0}) {
      CAPTURE(lambda);
      const Eigen::VectorXd lower = Eigen::VectorXd::Constant(2, -10.0), upper = Eigen::VectorXd::Constant(2, 10.0);
      const runtime::DampedStep a = whole.step(lambda, scale, lower, upper), b = small.step(lambda, scale, lower, upper);
      CHECK((a.d - b.d).norm() < step_tolerance * a.d.norm());
      CHECK(test::relative_error(a.predicted, b.predicted) < step_tolerance);
    }
    CHECK((reduced->r.transpose() * reduced->r).norm() > 0.0);
  }
}

TEST_CASE("reduced history Jacobian: a coordinate with no step gives a zero column and no moved phi") {
  const runtime::Network start = test::network_from(kStart, "t");
  const std::vector<int> free = runtime::bounded_parameters(start);
  const runtime::Coordinates coordinates(start, free);
  const std::vector<runtime::FitDataSet> data = measured({.given = true, .free = true});
  const auto reduced = runtime::reduced_history_jacobian([&](const std::vector<double>& at) { return coordinates.network(at); }, data,
                                                         runtime::ScoreSettings{}, coordinates.z0, {1e-6, 0.0});
  REQUIRE(reduced);
  CHECK(reduced->r.col(1).norm() == 0.0);
  CHECK(reduced->r.col(0).norm() > 0.0);
  CHECK(std::isnan(reduced->moved_values[1]));
}

TEST_CASE("fit on histories with the reduced Jacobian: the minimum of the whole-vector fit, the same standard errors") {
  const runtime::Network start = test::network_from(kStart, "t");
  const std::vector<int> free = runtime::bounded_parameters(start);
  const std::vector<runtime::FitDataSet> data = measured({.given = true, .free = true});
  runtime::FitSettings whole;
  whole.search.max_evaluations = 400;
  runtime::FitSettings reduced = whole;
  reduced.whole_jacobian_bytes = 0;
  const runtime::FitResult a = runtime::fit(start, free, data, whole), b = runtime::fit(start, free, data, reduced);
  CAPTURE(a.objective);
  CAPTURE(b.objective);
  CHECK(test::relative_error(b.objective, a.objective) < 1e-8);
  for (const int p : free) {
    const auto u = static_cast<std::size_t>(p);
    CHECK(test::relative_error(b.network.parameters()[u], a.network.parameters()[u]) < 1e-5);
  }
  // The truth's tau and yield force within the ripple's reach.
  CHECK(std::abs(b.network.parameters()[static_cast<std::size_t>(test::parameter_index(start, "m.tau"))] - 0.020) < 0.002);
  CHECK(std::abs(b.network.parameters()[static_cast<std::size_t>(test::parameter_index(start, "f.fy"))] - 12.0) < 1.2);
  REQUIRE(a.statistics.standard_error.size() == b.statistics.standard_error.size());
  for (std::size_t i = 0; i < a.statistics.standard_error.size(); ++i)
    CHECK(test::relative_error(b.statistics.standard_error[i], a.statistics.standard_error[i]) < 1e-3);
}

}  // namespace history_jacobian_test
