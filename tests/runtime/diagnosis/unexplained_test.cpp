// The shape of a residual no candidate explains (runtime/diagnosis/unexplained.hpp): where on
// the grid it lies, and which signal a history's force residual follows.
#include "runtime/diagnosis/unexplained.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <numbers>

namespace unexplained_test {

using namespace rheo;
namespace dx = runtime::diagnosis;

TEST_CASE("unexplained shape, harmonic: a miss at the two smallest amplitudes and 10-20 Hz is located there") {
  const std::vector<double> amplitudes{0.1, 0.2, 0.5, 1.0, 2.0}, frequencies{1, 5, 10, 15, 20, 30, 40};
  runtime::HarmonicData d;
  runtime::DataSetFit set;
  for (double a : amplitudes)
    for (double f : frequencies) {
      d.amplitude.push_back(a), d.frequency.push_back(f), d.stiffness.push_back(100.0), d.phase.push_back(0.1);
      const bool inside = a <= 0.2 && f >= 10 && f <= 20;
      set.prediction.points.emplace_back();
      set.residuals.stiffness.push_back(inside ? 0.1 : 0.001);
      set.residuals.damping.push_back(0.0);
    }
  runtime::FitResult fit{test::network_from("model m { spring s (k = 1 N/mm) }", "m")};
  fit.datasets.push_back(set);
  const dx::ResidualShape shape = dx::residual_shape(fit, {runtime::FitDataSet{"grid.csv", 1.0, d, {}}});
  REQUIRE(shape.amplitudes);
  REQUIRE(shape.frequencies);
  CHECK(shape.amplitudes->low == 0.1);
  CHECK(shape.amplitudes->high == 0.2);  // each holds just under half
  CHECK(shape.amplitudes->levels == 2);
  CHECK(shape.amplitudes->of == 5);
  CHECK(shape.frequencies->low >= 10.0);
  CHECK(shape.frequencies->high <= 20.0);
  CHECK(shape.frequencies->share >= 0.5);
  CHECK_FALSE(shape.resembles);
}

TEST_CASE("unexplained shape, history: a constant offset and a yield force are recognised") {
  for (const auto& [miss, expected] : std::vector<std::pair<std::function<double(double, double)>, dx::Resemblance>>{
           {[](double, double) { return -65.0; }, dx::Resemblance::offset},
           {[](double, double v) { return v > 0 ? 40.0 : -40.0; }, dx::Resemblance::yield_force},
           {[](double u, double) { return 3.0 * u * u; }, dx::Resemblance::even_law}}) {
    runtime::HistoryData h;
    runtime::DataSetFit set;
    for (int k = 0; k <= 800; ++k) {
      const double t = k / 400.0, u = 2.0 * std::sin(2.0 * std::numbers::pi * t), v = std::cos(2.0 * std::numbers::pi * t);
      h.drive.time.push_back(t), h.drive.displacement.push_back(u), h.force.push_back(300.0 * u);
      set.prediction.force.push_back(300.0 * u + miss(u, v));
    }
    h.force_scale = 600.0;
    runtime::FitResult fit{test::network_from("model m { spring s (k = 1 N/mm) }", "m")};
    fit.datasets.push_back(set);
    const dx::ResidualShape shape = dx::residual_shape(fit, {runtime::FitDataSet{"h.csv", 1.0, h, {}}});
    REQUIRE(shape.resembles);
    CHECK(*shape.resembles == expected);
    CHECK(shape.resembles_share > 0.5);
  }
}

}  // namespace unexplained_test
