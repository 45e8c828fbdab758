// Yeoh constants from the mean curve (5.28-5.36): exact on a pure yeoh spring, the mean curve
// against its closed form (elastic law + reversal-zone bias) on a yeoh + friction + Maxwell
// model, and the constants of the specimen D static test against Table D.4.
#include "runtime/fit/yeoh_mean_curve.hpp"

#include "runtime/protocols/run_history.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/fit/fit_statistics.hpp"
#include "support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace yeoh_mean_curve_test {

using namespace rheo;
using test::relative_error;

namespace {

constexpr runtime::YeohConstants kTableD4{389.4253, -2.1094, 0.0786};  // specimen D

runtime::LoopSamples loop_of(const runtime::History& h) { return {h.displacement, h.force}; }

std::string specimen_d_source(const std::string& extra) {
  return R"(
    model d {
      yeoh     rubber (D10 = 389.4253 N/mm, D20 = -2.1094 N/mm^3, D30 = 0.0786 N/mm^5)
      maxwell  m1 (k = 61.476 N/mm, tau = 0.004335 s)
      friction f1 (k = 1016.6 N/mm, uy = 101.58 um)
      friction f2 (k = 301.04 N/mm, uy = 42.256 um)
      friction f3 (k = 25.516 N/mm, uy = 12.695 um)
      friction f4 (k = 33.918 N/mm, uy = 17.763 um)
      friction f5 (k = 54.962 N/mm, uy = 35.116 um)
      friction f6 (k = 84.955 N/mm, uy = 110.68 um)
      )" +
         extra + "\n    }";
}

}  // namespace

TEST_CASE("a pure yeoh spring's loop gives its constants to 1e-10") {
  const auto net = test::network_from("model y { yeoh r (D10 = 389.4253, D20 = -2.1094, D30 = 0.0786) }", "y");
  const auto drive = runtime::static_triangle({6.25, 3.0}, 0.05, 2, 400);
  const auto loop = runtime::largest_loop(loop_of(runtime::run_history(net, drive, false)));
  // The second 6.25 mm cycle: samples 400..800 of the drive.
  REQUIRE(loop.displacement.size() == 401);
  CHECK(loop.displacement.front() == drive.displacement[400]);
  CHECK(loop.displacement.back() == drive.displacement[800]);
  CHECK(*std::max_element(loop.displacement.begin(), loop.displacement.end()) == 6.25);
  const auto curve = runtime::mean_curve(loop);
  // 5 % of 12.5 mm dropped at each end: [-5.625, 5.625] at 0.0625 mm, 181 points.
  CHECK(curve.displacement.size() == 181);
  CHECK(curve.displacement.front() == doctest::Approx(-5.625));
  const auto d = runtime::fit_yeoh_least_squares(curve);
  CHECK(relative_error(d.d10, kTableD4.d10) < 1e-10);
  CHECK(relative_error(d.d20, kTableD4.d20) < 1e-10);
  CHECK(relative_error(d.d30, kTableD4.d30) < 1e-10);
}

TEST_CASE("mean curve: branches sampled differently are interpolated, a closed cycle's split branch is joined") {
  // Linear branches F = 2 u +- 10 (interpolation is exact for them): loading sampled at 0.1 mm,
  // unloading at 0.07 mm steps, one cycle 0 -> 1 -> -1 -> 0 starting mid-loading. The branches
  // jump at the tips (each run shares its turning sample with the next), which the default
  // margin (0.1 mm here) removes.
  runtime::LoopSamples loop;
  auto add = [&](double u, double f) {
    loop.displacement.push_back(u);
    loop.force.push_back(f);
  };
  for (int k = 0; k <= 10; ++k) add(0.1 * k, 2 * 0.1 * k + 10);
  for (double u = 1.0 - 0.07; u > -1.0; u -= 0.07) add(u, 2 * u - 10);
  for (int k = -10; k <= 0; ++k) add(0.1 * k, 2 * 0.1 * k + 10);
  const auto curve = runtime::mean_curve(loop);
  REQUIRE(curve.displacement.size() > 40);
  CHECK(curve.displacement.front() >= -0.9 - 1e-12);
  CHECK(curve.displacement.front() < -0.85);
  CHECK(curve.displacement.back() <= 0.9 + 1e-12);
  CHECK(curve.displacement.back() > 0.85);
  for (std::size_t i = 0; i < curve.displacement.size(); ++i) {
    if (i > 0) CHECK(curve.displacement[i] > curve.displacement[i - 1]);
    CHECK(std::abs(curve.force[i] - 2 * curve.displacement[i]) < 1e-12);
  }
  const auto d = runtime::fit_yeoh_least_squares(curve);
  CHECK(d.d10 == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(std::abs(d.d20) < 1e-12);
  CHECK(std::abs(d.d30) < 1e-12);
}

TEST_CASE("yeoh + friction + Maxwell: the mean curve is the elastic law plus the reversal-zone bias") {
  // Specimen D plus a slow Maxwell element (k = 20, t_r = 2 s, c v = 2 N, v t_r = 0.1 mm) so that
  // the viscous reversal transient reaches into the loop. Static triangle 6.25 mm at 0.05 mm/s.
  const double v = 0.05, amplitude = 6.25;
  const auto net = test::network_from(specimen_d_source("maxwell slow (k = 20 N/mm, tau = 2 s)"), "d");
  const auto loop = runtime::largest_loop(loop_of(runtime::run_history(net, runtime::static_triangle({amplitude}, v, 2, 400), false)));
  // Closed form of the mean with no margin (header of yeoh_mean_curve.hpp): distance s to the
  // nearer turning point, sign of that point; the drive's kernels are exact for the triangle.
  // The elastic law is eq. 3.3 as the tests write it (support.hpp), not runtime::YeohLaw, which
  // the simulation of the loop uses.
  const double kp[] = {1016.6, 301.04, 25.516, 33.918, 54.962, 84.955};
  const double us[] = {0.10158, 0.042256, 0.012695, 0.017763, 0.035116, 0.11068};
  const double taus[] = {0.004335, 2.0}, ks[] = {61.476, 20.0};
  auto elastic = [](double u) { return test::yeoh_force(kTableD4.d10, kTableD4.d20, kTableD4.d30, u); };  // eq. 3.3
  auto predicted = [&](double u) {
    const double s = amplitude - std::abs(u), sign = u > 0 ? 1.0 : -1.0;
    double bias = 0.0;
    for (int q = 0; q < 6; ++q) bias += std::max(0.0, kp[q] * us[q] - kp[q] * s / 2);
    for (int j = 0; j < 2; ++j) bias += ks[j] * taus[j] * v * std::exp(-s / (v * taus[j]));
    return elastic(u) + sign * bias;
  };
  const auto full = runtime::mean_curve(loop, 0.0);
  double worst = 0.0, largest_bias = 0.0;
  for (std::size_t i = 0; i < full.displacement.size(); ++i) {
    worst = std::max(worst, std::abs(full.force[i] - predicted(full.displacement[i])));
    largest_bias = std::max(largest_bias, std::abs(full.force[i] - elastic(full.displacement[i])));
  }
  MESSAGE(fmt::format("mean curve vs closed form: worst {:.2e} N; largest bias at the tips {:.1f} N", worst, largest_bias));
  CHECK(worst < 1e-8);
  CHECK(largest_bias > 100.0);  // sum F_y = 128 N at the tips, + 2 N viscous

  // With the tips kept, the bias is odd in u and leaks into the constants.
  const auto biased = runtime::fit_yeoh_least_squares(full);
  // With the default margin (0.625 mm = 6.25 v t_r of the slow element; the friction zone is
  // 0.22 mm) what remains is the viscous tail 2 N e^{-6.25} = 4e-3 N at the edge, decaying inward.
  const auto d = runtime::fit_yeoh_least_squares(runtime::mean_curve(loop));
  MESSAGE(fmt::format("constants, tips kept: {:.4f} {:.5f} {:.6f}; default margin: {:.6f} {:.7f} {:.8f} (true 389.4253 -2.1094 0.0786)", biased.d10,
                      biased.d20, biased.d30, d.d10, d.d20, d.d30));
  CHECK(relative_error(biased.d30, kTableD4.d30) > 1e-3);
  CHECK(relative_error(d.d10, kTableD4.d10) < 1e-5);
  CHECK(relative_error(d.d20, kTableD4.d20) < 1e-4);
  CHECK(relative_error(d.d30, kTableD4.d30) < 1e-4);
}

TEST_CASE("specimen D static test: the constants of Table D.4 within the data's noise") {
  // The data carry Gaussian force noise sigma = 0.3 % of max |F| per sample; a mean-curve point
  // averages two samples (the branches are sampled at the same displacements), so the fit's
  // residual must be sigma / sqrt(2), and the constants must lie within 3 of their standard
  // errors (fit_statistics.hpp, an OLS fit of the same columns) of Table D.4.
  const auto table = runtime::read_table(std::string(RHEO_DATA_DIR) + "/specimen_D_static.csv");
  const auto history = runtime::loop_samples_from_table(table);
  const auto loop = runtime::largest_loop(history);
  REQUIRE(loop.displacement.size() == 401);
  const auto curve = runtime::mean_curve(loop);
  const auto d = runtime::fit_yeoh_least_squares(curve);
  auto residuals = [&](const std::vector<double>& z) {
    std::vector<double> r;
    for (std::size_t i = 0; i < curve.displacement.size(); ++i)
      r.push_back(curve.force[i] - test::yeoh_force(z[0], z[1], z[2], curve.displacement[i]));
    return r;
  };
  const auto st = runtime::parameter_statistics(residuals, {d.d10, d.d20, d.d30}, {false, false, false});
  double rss = 0.0, largest = 0.0;
  for (double r : residuals({d.d10, d.d20, d.d30})) rss += r * r;
  for (double f : history.force) largest = std::max(largest, std::abs(f));
  const double s = std::sqrt(rss / static_cast<double>(curve.displacement.size() - 3));
  const double sigma = 0.003 * largest / std::sqrt(2.0);
  const double fitted[] = {d.d10, d.d20, d.d30}, truth[] = {kTableD4.d10, kTableD4.d20, kTableD4.d30};
  MESSAGE(fmt::format(
      "specimen_D_static.csv (last 6.25 mm cycle, {} mean points): D10 = {:.4f} ({:+.3f} %, {:+.2f} SE), "
      "D20 = {:.5f} ({:+.3f} %, {:+.2f} SE), D30 = {:.6f} ({:+.3f} %, {:+.2f} SE); residual {:.2f} N = {:.3f} x noise",
      curve.displacement.size(), d.d10, 100 * (d.d10 / truth[0] - 1), (d.d10 - truth[0]) / st.standard_error[0], d.d20, 100 * (d.d20 / truth[1] - 1),
      (d.d20 - truth[1]) / st.standard_error[1], d.d30, 100 * (d.d30 / truth[2] - 1), (d.d30 - truth[2]) / st.standard_error[2], s, s / sigma));
  CHECK(s / sigma > 0.85);
  CHECK(s / sigma < 1.15);
  for (int j = 0; j < 3; ++j) {
    CAPTURE(j);
    CHECK(std::abs(fitted[j] - truth[j]) < 3.0 * st.standard_error[static_cast<std::size_t>(j)]);
  }
  // Observed +0.35 %, +2.6 %, +0.84 % (1.7, 1.1, 0.7 SE; SE = 0.21 %, 2.4 %, 1.2 %).
  CHECK(relative_error(d.d10, truth[0]) < 0.01);
  CHECK(relative_error(d.d20, truth[1]) < 0.04);
  CHECK(relative_error(d.d30, truth[2]) < 0.02);
}

TEST_CASE("shape transfer (5.33-5.36): D10 = K_e / 2, the ratios kept") {
  const auto d = runtime::yeoh_from_shape({400.0, -2.0, 0.08}, 700.0);
  CHECK(d.d10 == 350.0);
  CHECK(d.d20 == doctest::Approx(-2.0 * 350.0 / 400.0).epsilon(1e-15));
  CHECK(d.d30 == doctest::Approx(0.08 * 350.0 / 400.0).epsilon(1e-15).scale(0.0));
  CHECK_THROWS_AS(runtime::yeoh_from_shape({0.0, 1.0, 1.0}, 700.0), runtime::NumericalError);
  CHECK_THROWS_AS(runtime::yeoh_from_shape({1.0, 1.0, 1.0}, 0.0), std::logic_error);
}

TEST_CASE("loops without both branches, tables without the columns and degenerate curves are refused") {
  runtime::LoopSamples ramp{{0.0, 1.0, 2.0, 3.0}, {0.0, 1.0, 2.0, 3.0}};
  CHECK_THROWS_AS(runtime::mean_curve(ramp), runtime::DataError);
  CHECK_THROWS_AS(runtime::largest_loop(ramp), runtime::DataError);
  CHECK_THROWS_AS(runtime::mean_curve(ramp, 0.5), std::logic_error);
  CHECK_THROWS_AS(runtime::mean_curve({{0.0, 1.0}, {0.0}}), std::logic_error);
  const auto table = runtime::parse_table("t.csv", "time [s],displacement [mm]\n0,0\n1,1\n");
  CHECK_THROWS_WITH_AS(runtime::loop_samples_from_table(table), doctest::Contains("'force'"), runtime::DataError);
  CHECK_THROWS_AS(runtime::fit_yeoh_least_squares({{0.0, 0.0, 0.0}, {1.0, 2.0, 3.0}}), runtime::NumericalError);
  CHECK_THROWS_AS(runtime::fit_yeoh_least_squares({{1.0, 2.0}, {1.0, 2.0}}), std::logic_error);
}

TEST_CASE("yeoh start values: the loop's constants, free ones clamped into their bounds, fixed ones marked") {
  // A pure yeoh spring's loop holds its constants exactly; D10's bounds exclude the true value.
  const std::string source = "model y { yeoh r (D10 = 100 N/mm in [10, 300], D20 = -1 N/mm^3 in [-10, 10], D30 = 0.05 N/mm^5) }";
  const lang::CheckedModel model = test::model_from(source, "y");
  const auto truth = test::network_from("model t { yeoh r (D10 = 389.4253 N/mm, D20 = -2.1094 N/mm^3, D30 = 0.0786 N/mm^5) }", "t");
  const auto loop = loop_of(runtime::run_history(truth, runtime::static_triangle({3.0}, 0.05, 2, 400), false));
  const std::array<int, 3> yeoh{model.root.children[0].parameters[0], model.root.children[0].parameters[1], model.root.children[0].parameters[2]};
  const std::vector<int> free{yeoh[0], yeoh[1]};  // D30 has no bounds: fixed
  const auto started = runtime::yeoh_start_values(model, yeoh, free, loop);
  CHECK(started[0].parameter == yeoh[0]);
  CHECK(relative_error(started[0].unclamped, kTableD4.d10) < 1e-9);
  CHECK(started[0].value == 300.0);  // clamped into [10, 300]
  CHECK(started[0].free);
  CHECK(relative_error(started[1].value, kTableD4.d20) < 1e-9);  // inside its bounds
  CHECK(started[1].value == started[1].unclamped);
  CHECK_FALSE(started[2].free);
  CHECK(relative_error(started[2].unclamped, kTableD4.d30) < 1e-9);
  CHECK_THROWS_AS(runtime::yeoh_start_values(model, yeoh, free, {{0.0, 1.0, 2.0}, {0.0, 1.0, 2.0}}), runtime::DataError);
}

}  // namespace yeoh_mean_curve_test
