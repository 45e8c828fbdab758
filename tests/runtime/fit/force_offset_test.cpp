// Force offsets of measured histories (runtime/fit/force_offset.hpp): the least-squares offset
// by hand, parameters and offset recovered from a history generated with a known offset, the
// declared offset against the fitted one, the fit without it measurably worse, and the
// standard errors against the closed form of linear regression with an intercept.
#include "runtime/fit/force_offset.hpp"

#include "runtime/fit/fit.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>

#include <cmath>
#include <numeric>

namespace force_offset_test {

using namespace rheo;

namespace {

runtime::FitDataSet with_offset(runtime::FitDataSet set, bool free, double value = 0.0) {
  set.force_offset = {.given = true, .free = free, .value = value};
  return set;
}

// A spring and a Maxwell element: tau is a shape parameter, both k force scales.
const char* kTruth = "model t { spring e (k = 100 N/mm) maxwell m (k = 50 N/mm, tau = 20 ms) }";
const char* kStart = R"(model t {
  spring e (k = 300 N/mm in [1, 10000])
  maxwell m (k = 150 N/mm in [1, 10000], tau = 60 ms in [0.1, 10000]) })";
constexpr double kOffset = 150.0;  // N

runtime::FitDataSet generated(double offset) {
  return test::history_data_of(test::network_from(kTruth, "t"), runtime::quasistatic_sine({1.0, 0.3}, 2.0, 2, 400), "rig.csv", 1.0, offset);
}

void check_recovered(const runtime::FitResult& r) {
  const runtime::Network truth = test::network_from(kTruth, "t");
  for (const char* path : {"e.k", "m.k", "m.c"}) {
    CAPTURE(path);
    CHECK(test::relative_error(r.network.parameter(test::parameter_index(r.network, path)), truth.parameter(test::parameter_index(truth, path))) <
          1e-6);
  }
}

}  // namespace

TEST_CASE("force_offset: declared as given, free the mean of measured - predicted, none or a harmonic table 0") {
  runtime::HistoryData h;
  h.force = {10.0, 20.0, 60.0};
  h.force_scale = 60.0;
  const runtime::FitDataSet plain{"h.csv", 1.0, h};
  const std::vector<double> network{1.0, 2.0, 3.0};
  CHECK(runtime::force_offset(plain, network, runtime::Offsets::applied) == 0.0);
  CHECK(runtime::force_offset(with_offset(plain, false, -120.0), network, runtime::Offsets::applied) == -120.0);
  CHECK(runtime::force_offset(with_offset(plain, false, -120.0), network, runtime::Offsets::declared) == -120.0);
  CHECK(runtime::force_offset(with_offset(plain, false, -120.0), network, runtime::Offsets::none) == 0.0);
  CHECK(runtime::force_offset(with_offset(plain, true), network, runtime::Offsets::applied) == doctest::Approx((9.0 + 18.0 + 57.0) / 3.0));
  CHECK(runtime::force_offset(with_offset(plain, true), network, runtime::Offsets::declared) == 0.0);
  runtime::HarmonicData d;
  CHECK(runtime::force_offset(with_offset({"g.csv", 1.0, d}, false, 50.0), {}, runtime::Offsets::applied) == 0.0);
}

TEST_CASE("a free offset is eliminated exactly: the scored residuals are orthogonal to it and minimal in it") {
  const runtime::Network truth = test::network_from(kTruth, "t");
  const runtime::FitDataSet set = with_offset(generated(kOffset), true);
  std::vector<double> values = truth.parameters();
  for (double& v : values) v *= 1.3;  // off the truth
  const runtime::Network other = truth.with_parameters(values);
  const runtime::Prediction p = runtime::predict(other, set, runtime::FitMethod::exact, {}, nullptr);
  std::vector<double> r;
  runtime::append_residuals(set, p, {}, r);
  double sum = 0.0, squares = 0.0;
  for (double v : r) sum += v, squares += v * v;
  CHECK(std::abs(sum) < 1e-12 * std::sqrt(squares * static_cast<double>(r.size())));
  // Moving the offset either way raises the sum of squares.
  for (double delta : {-1.0, 1.0}) {
    runtime::Prediction moved = p;
    for (double& f : moved.force) f += delta;
    std::vector<double> rm;
    runtime::append_residuals(set, moved, {}, rm);
    CHECK(std::inner_product(rm.begin(), rm.end(), rm.begin(), 0.0) > squares);
  }
}

TEST_CASE("a history with a load-cell offset: parameters and offset recovered, on the separable path and the plain search") {
  const runtime::Network start = test::network_from(kStart, "t");
  for (const bool separable : {true, false}) {
    CAPTURE(separable);
    runtime::FitSettings settings;
    settings.separable = separable;
    const runtime::FitResult r = runtime::fit(start, runtime::bounded_parameters(start), {with_offset(generated(kOffset), true)}, settings);
    check_recovered(r);
    const runtime::FittedOffset& o = r.datasets.at(0).force_offset;
    CHECK(o.free);
    CHECK(std::abs(o.value - kOffset) < 1e-6 * kOffset);
    CHECK(r.datasets[0].err < 1e-8);  // the noise floor of noise-free data
  }
}

TEST_CASE("the true offset declared fits as the free one does, without an offset the fit is measurably worse") {
  const runtime::Network start = test::network_from(kStart, "t");
  const auto free = runtime::bounded_parameters(start);
  const runtime::FitResult fitted = runtime::fit(start, free, {with_offset(generated(kOffset), true)}, {});
  const runtime::FitResult declared = runtime::fit(start, free, {with_offset(generated(kOffset), false, kOffset)}, {});
  check_recovered(declared);
  for (int i : free) CHECK(test::relative_error(declared.network.parameter(i), fitted.network.parameter(i)) < 1e-6);
  CHECK(declared.datasets[0].force_offset.value == kOffset);
  CHECK(declared.datasets[0].err < 1e-8);
  const runtime::FitResult ignored = runtime::fit(start, free, {generated(kOffset)}, {});
  CAPTURE(ignored.datasets[0].err);
  CHECK(ignored.datasets[0].err > 0.05);  // a constant no element of the network can carry
  CHECK(ignored.datasets[0].err > 1e4 * fitted.datasets[0].err);
}

// F = k u + c is linear regression on [u, 1]: the fit, the standard errors and the correlation
// of k and c have closed forms (Cov = s^2 (X^T X)^-1, s^2 = RSS / (M - 2)).
TEST_CASE("standard errors of a spring and a free offset: the closed form of linear regression with an intercept") {
  const runtime::Network start = test::network_from("model s { spring e (k = 10 N/mm in [1, 1000]) }", "s");
  runtime::HistoryData h;
  const int samples = 200;
  for (int j = 0; j < samples; ++j) {
    const double u = 0.5 + std::sin(0.05 * j);
    h.drive.time.push_back(0.01 * j);
    h.drive.displacement.push_back(u);
    h.force.push_back(80.0 * u + 40.0 + 0.5 * std::sin(7.3 * j));  // a deterministic stand-in for noise
    h.rows.push_back(j + 2);
  }
  for (double f : h.force) h.force_scale = std::max(h.force_scale, std::abs(f));
  const runtime::FitResult r = runtime::fit(start, {0}, {with_offset({"line.csv", 1.0, h}, true)}, {});

  Eigen::MatrixXd x(samples, 2);
  Eigen::VectorXd y(samples);
  for (int j = 0; j < samples; ++j)
    x(j, 0) = h.drive.displacement[static_cast<std::size_t>(j)], x(j, 1) = 1.0, y(j) = h.force[static_cast<std::size_t>(j)];
  const Eigen::Vector2d beta = (x.transpose() * x).ldlt().solve(x.transpose() * y);
  const double s2 = (y - x * beta).squaredNorm() / (samples - 2);
  const Eigen::Matrix2d cov = s2 * (x.transpose() * x).inverse();

  const runtime::FittedOffset& o = r.datasets.at(0).force_offset;
  CHECK(test::relative_error(r.network.parameter(0), beta(0)) < 1e-9);
  CHECK(test::relative_error(o.value, beta(1)) < 1e-9);
  REQUIRE(r.statistics.standard_error.size() == 1);
  CHECK(test::relative_error(r.statistics.standard_error[0], std::sqrt(cov(0, 0))) < 1e-6);
  CHECK(test::relative_error(o.standard_error, std::sqrt(cov(1, 1))) < 1e-6);
  REQUIRE(o.correlation.size() == 1);
  CHECK(o.correlation[0] == doctest::Approx(cov(0, 1) / std::sqrt(cov(0, 0) * cov(1, 1))).epsilon(1e-6).scale(0.0));
  CHECK(o.identifiable);
}

TEST_CASE("an offset the data cannot tell from the model is reported not identifiable") {
  // A constant displacement: the spring's force k u is a constant too.
  const runtime::Network start = test::network_from("model s { spring e (k = 10 N/mm in [1, 1000]) }", "s");
  runtime::HistoryData h;
  for (int j = 0; j < 20; ++j) {
    h.drive.time.push_back(0.01 * j);
    h.drive.displacement.push_back(1.0);
    h.force.push_back(50.0 + 0.1 * std::sin(3.0 * j));
    h.rows.push_back(j + 2);
  }
  h.force_scale = 51.0;
  const runtime::FitResult r = runtime::fit(start, {0}, {with_offset({"flat.csv", 1.0, h}, true)}, {});
  CHECK_FALSE(r.datasets.at(0).force_offset.identifiable);
  CHECK_FALSE(r.statistics.identifiable.at(0));
}

}  // namespace force_offset_test
