// Parameter statistics at a least-squares optimum against the closed form of straight-line
// regression, the delta method for log coordinates, and rank-deficient parametrisations.
#include "runtime/fit/fit_statistics.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

namespace fit_statistics_test {

using runtime_stats = rheo::runtime::ParameterStatistics;
using rheo::runtime::parameter_statistics;

namespace {

// y = a + b x with deterministic "noise"; the textbook closed form:
//   b = Sxy / Sxx, a = ybar - b xbar, s^2 = sum r^2 / (m - 2),
//   SE(b) = s / sqrt(Sxx), SE(a) = s sqrt(1/m + xbar^2 / Sxx), corr(a, b) = -xbar / sqrt(Sxx/m + xbar^2).
struct Line {
  std::vector<double> x, y;
  double a = 0, b = 0, se_a = 0, se_b = 0, corr = 0;
  Line() {
    const int m = 20;
    for (int i = 0; i < m; ++i) {
      x.push_back(0.5 * i + 1.0);
      y.push_back(1.5 + 0.3 * x.back() + 0.1 * std::sin(7.3 * i));
    }
    double xbar = 0, ybar = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      xbar += x[i] / m;
      ybar += y[i] / m;
    }
    double sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      sxx += (x[i] - xbar) * (x[i] - xbar);
      sxy += (x[i] - xbar) * (y[i] - ybar);
    }
    b = sxy / sxx;
    a = ybar - b * xbar;
    double rss = 0;
    for (std::size_t i = 0; i < x.size(); ++i) rss += std::pow(y[i] - a - b * x[i], 2);
    const double s = std::sqrt(rss / (m - 2));
    se_b = s / std::sqrt(sxx);
    se_a = s * std::sqrt(1.0 / m + xbar * xbar / sxx);
    corr = -xbar / std::sqrt(sxx / m + xbar * xbar);
  }
  std::vector<double> residuals(double intercept, double slope) const {
    std::vector<double> r;
    for (std::size_t i = 0; i < x.size(); ++i) r.push_back(y[i] - intercept - slope * x[i]);
    return r;
  }
};

}  // namespace

TEST_CASE("straight line: standard errors and correlation of the closed form") {
  const Line line;
  const auto st = parameter_statistics([&](const std::vector<double>& z) { return line.residuals(z[0], z[1]); }, {line.a, line.b}, {false, false});
  CHECK(st.rank == 2);
  CHECK(st.identifiable == std::vector<bool>{true, true});
  CHECK(st.standard_error[0] == doctest::Approx(line.se_a).epsilon(1e-7).scale(0.0));
  CHECK(st.standard_error[1] == doctest::Approx(line.se_b).epsilon(1e-7).scale(0.0));
  CHECK(st.correlation[0][1] == doctest::Approx(line.corr).epsilon(1e-7).scale(0.0));
  CHECK(st.correlation[1][0] == doctest::Approx(line.corr).epsilon(1e-7).scale(0.0));
  CHECK(st.correlation[0][0] == 1.0);
}

TEST_CASE("log coordinates: p = exp(z) gives the parameter-space statistics (delta method)") {
  const Line line;
  REQUIRE(line.a > 0);
  // Intercept searched as z0 = ln a: the same line, so the same statistics in parameter units.
  const auto st = parameter_statistics([&](const std::vector<double>& z) { return line.residuals(std::exp(z[0]), z[1]); },
                                       {std::log(line.a), line.b}, {true, false});
  CHECK(st.standard_error[0] == doctest::Approx(line.se_a).epsilon(1e-7).scale(0.0));
  CHECK(st.standard_error[1] == doctest::Approx(line.se_b).epsilon(1e-7).scale(0.0));
  CHECK(st.correlation[0][1] == doctest::Approx(line.corr).epsilon(1e-7).scale(0.0));

  // Non-linear model y = A exp(-x / tau) at an arbitrary point: log and linear coordinates agree.
  auto model = [&](double amplitude, double tau) {
    std::vector<double> r;
    for (std::size_t i = 0; i < line.x.size(); ++i) r.push_back(line.y[i] - amplitude * std::exp(-line.x[i] / tau));
    return r;
  };
  const double amplitude = 4.0, tau = 12.0;
  const auto lin = parameter_statistics([&](const std::vector<double>& z) { return model(z[0], z[1]); }, {amplitude, tau}, {false, false});
  const auto log = parameter_statistics([&](const std::vector<double>& z) { return model(std::exp(z[0]), std::exp(z[1])); },
                                        {std::log(amplitude), std::log(tau)}, {true, true});
  CHECK(log.standard_error[0] == doctest::Approx(lin.standard_error[0]).epsilon(1e-7));
  CHECK(log.standard_error[1] == doctest::Approx(lin.standard_error[1]).epsilon(1e-7));
  CHECK(log.correlation[0][1] == doctest::Approx(lin.correlation[0][1]).epsilon(1e-7).scale(0.0));
}

TEST_CASE("rank deficiency: only the estimable parameters get finite statistics") {
  const Line line;
  // a and c enter only as a + c: the direction (1, 0, -1) is not resolved.
  const auto sum = parameter_statistics([&](const std::vector<double>& z) { return line.residuals(z[0] + z[2], z[1]); },
                                        {0.5 * line.a, line.b, 0.5 * line.a}, {false, false, false});
  CHECK(sum.rank == 2);
  CHECK(sum.identifiable == std::vector<bool>{false, true, false});
  CHECK(sum.standard_error[1] == doctest::Approx(line.se_b).epsilon(1e-7).scale(0.0));  // s^2 with m - rank degrees of freedom
  CHECK(std::isinf(sum.standard_error[0]));
  CHECK(std::isinf(sum.standard_error[2]));
  CHECK(std::isnan(sum.correlation[0][1]));
  CHECK(sum.correlation[2][2] == 1.0);

  // A parameter that does not enter at all leaves the others' statistics untouched.
  const auto unused = parameter_statistics([&](const std::vector<double>& z) { return line.residuals(z[0], z[1]); }, {line.a, line.b, 7.0},
                                           {false, false, true});
  CHECK(unused.rank == 2);
  CHECK(unused.identifiable == std::vector<bool>{true, true, false});
  CHECK(unused.standard_error[0] == doctest::Approx(line.se_a).epsilon(1e-7).scale(0.0));
  CHECK(unused.correlation[0][1] == doctest::Approx(line.corr).epsilon(1e-7).scale(0.0));
}

TEST_CASE("without a degree of freedom: identifiability and correlation, but no standard errors, sizes must agree") {
  // r = (1 - z0 - z1, 2 - z0 - 2 z1): J = -[[1, 1], [1, 2]], full rank, m = rank = 2.
  const auto two = [](const std::vector<double>& z) { return std::vector<double>{1.0 - z[0] - z[1], 2.0 - z[0] - 2 * z[1]}; };
  const auto exact = parameter_statistics(two, {0.0, 1.0}, {false, false});
  CHECK(exact.rank == 2);
  CHECK(!exact.has_noise_estimate());
  CHECK(exact.identifiable == std::vector<bool>{true, true});
  CHECK(std::isnan(exact.standard_error[0]));
  CHECK(std::isnan(exact.standard_error[1]));
  // (J^T J)^-1 = [[5, -3], [-3, 2]]: correlation -3 / sqrt(10).
  CHECK(exact.correlation[0][1] == doctest::Approx(-3.0 / std::sqrt(10.0)).epsilon(1e-7).scale(0.0));
  // One residual for two coordinates: rank 1, neither identifiable alone.
  const auto one = parameter_statistics([](const std::vector<double>& z) { return std::vector<double>{1.0 - z[0] - z[1]}; }, {0.3, 0.7},
                                        {false, false});
  CHECK(one.rank == 1);
  CHECK(one.identifiable == std::vector<bool>{false, false});
  CHECK_THROWS_AS(parameter_statistics(two, {0.0, 1.0}, {false}), std::logic_error);
  int calls = 0;
  const auto growing = [&](const std::vector<double>&) { return std::vector<double>(static_cast<std::size_t>(3 + calls++), 1.0); };
  CHECK_THROWS_AS(parameter_statistics(growing, {0.0}, {false}), std::logic_error);
}

TEST_CASE("groups that act together count the combinations the data leave free") {
  const Line line;
  // Intercept a = z0 + z2 + z3 and slope b = z1 + z4: {0, 2, 3} span 2 undetermined directions
  // (one combination fixed), {1, 4} one; the subspace's basis does not matter.
  const auto st = parameter_statistics([&](const std::vector<double>& z) { return line.residuals(z[0] + z[2] + z[3], z[1] + z[4]); },
                                       {0.2 * line.a, 0.5 * line.b, 0.3 * line.a, 0.5 * line.a, 0.5 * line.b}, {false, false, false, false, false});
  CHECK(st.rank == 2);
  REQUIRE(st.together.size() == 2);
  REQUIRE(st.undetermined.size() == 2);
  CHECK(st.together[0] == std::vector<int>{0, 2, 3});
  CHECK(st.undetermined[0] == 2);
  CHECK(st.together[1] == std::vector<int>{1, 4});
  CHECK(st.undetermined[1] == 1);
}

}  // namespace fit_statistics_test
