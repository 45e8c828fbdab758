// The global look of a candidate's refit (global_look.hpp): the screened start first, then the
// sampled points; positive parameters log-uniform over what the data support, a position (a
// gap's centre, bounds about zero) uniform over its bounds, other signed parameters kept.
#include "runtime/diagnosis/global_look.hpp"

#include "lang/frontend.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

namespace global_look_test {

using namespace rheo;
namespace dx = runtime::diagnosis;

namespace {

runtime::FitDataSet table() {
  runtime::HarmonicData h;
  h.path = "t.csv";
  h.amplitude = {0.1, 0.3, 1.0, 0.1, 0.3, 1.0};
  h.frequency = {1.0, 1.0, 1.0, 10.0, 10.0, 10.0};
  h.stiffness = {300.0, 320.0, 400.0, 310.0, 330.0, 410.0};
  h.phase = {0.05, 0.05, 0.05, 0.06, 0.06, 0.06};
  h.rows = {2, 3, 4, 5, 6, 7};
  return {"t.csv", 1.0, h};
}

}  // namespace

TEST_CASE("global look: the start first, a gap's centre sampled over both signs, widths and stiffnesses log-uniform in their range") {
  const lang::Program program = lang::compile_source("g.rheo", R"(model m {
  spring s (k = 300 N/mm)
  series b { gap g (width = 0.4 mm in [0.001, 5], center = 0 mm in [-1, 1])  spring k (k = 200 N/mm in [1, 10000]) }
  yeoh y (D10 = 10 N/mm, D20 = 0 N/mm^3 in [-1, 1], D30 = 0 N/mm^5)
})");
  const runtime::Network start = runtime::Network::compile(program.models.front());
  const int width = test::parameter_index(start, "b.g.width"), center = test::parameter_index(start, "b.g.center");
  const int k = test::parameter_index(start, "b.k.k"), d20 = test::parameter_index(start, "y.D20");
  const std::vector<runtime::FitDataSet> data{table()};
  runtime::ScoreSettings score;
  const int samples = 24;
  const std::vector<dx::SampledStart> points = dx::global_look(start, {width, center, k, d20}, data, score, samples, samples + 1);
  REQUIRE(points.size() == static_cast<std::size_t>(samples + 1));
  CHECK(points.front().values == start.parameters());
  double lowest = 1.0, highest = -1.0;
  for (std::size_t j = 1; j < points.size(); ++j) {
    const std::vector<double>& v = points[j].values;
    const double c = v[static_cast<std::size_t>(center)];
    CHECK(c >= -1.0);
    CHECK(c <= 1.0);
    lowest = std::min(lowest, c), highest = std::max(highest, c);
    const auto [w_lo, w_hi] = dx::supported_range(start, width, data, dx::data_scales(data));
    CHECK(v[static_cast<std::size_t>(width)] >= w_lo * (1 - 1e-12));
    CHECK(v[static_cast<std::size_t>(width)] <= w_hi * (1 + 1e-12));
    CHECK(v[static_cast<std::size_t>(d20)] == 0.0);  // signed, not a position: kept
    CHECK(std::isfinite(points[j].objective));
    if (j > 1) CHECK(points[j - 1].objective <= points[j].objective);  // best first after the start
  }
  // 24 Halton points (base 3 for the centre) cover [-1, 1]: both ends within a tenth.
  CHECK(lowest < -0.8);
  CHECK(highest > 0.8);
}

// A column (a chamber k onto a mass m and a channel c in parallel) that the band can see:
// resonating at 1-10 Hz, the measured frequencies, with a damping ratio 0.1-1 and a chamber of
// K/100 to K (K = 330 N/mm, the table's median stiffness). Its mass and damping lie within
// their supported ranges; a decade either side of the start's mass (a column resonating at
// 300 Hz) reaches 95 Hz on its chamber, not the band.
TEST_CASE("global look: masses and dampings range over the columns that resonate within the measured band") {
  const lang::Program program = lang::compile_source("g.rheo", R"(model m {
  spring s (k = 300 N/mm)
  series c { spring k (k = 30 N/mm in [0.01, 10000])  parallel y { inerter b (b = 0.0084 kg in [1e-9, 1e9])  dashpot d (c = 0.005 N*s/mm in [1e-9, 1e9]) } }
})");
  const runtime::Network start = runtime::Network::compile(program.models.front());
  const std::vector<runtime::FitDataSet> data{table()};
  const dx::DataScales scales = dx::data_scales(data);
  const auto [m_lo, m_hi] = dx::supported_range(start, test::parameter_index(start, "c.y.b.b"), data, scales);
  const auto [c_lo, c_hi] = dx::supported_range(start, test::parameter_index(start, "c.y.d.c"), data, scales);
  const double big_k = scales.bounds.stiffness, two_pi = 2.0 * std::acos(-1.0);
  for (double k : {big_k / 100.0, big_k})
    for (double f : {1.0, 10.0})
      for (double zeta : {0.1, 1.0}) {
        const double w = two_pi * f, m = k / (w * w), c = 2.0 * zeta * std::sqrt(k * m);
        INFO("k = " << k << " N/mm, f = " << f << " Hz, zeta = " << zeta);
        CHECK(m >= m_lo);
        CHECK(m <= m_hi);
        CHECK(c >= c_lo);
        CHECK(c <= c_hi);
      }
  CHECK(big_k == 330.0);
  // No wider than those columns need: stiffnesses over 900 times, frequencies over 10 times
  // (squared for a mass; a time's 3 either side for a damping). The parameters' own bounds
  // span 18 decades.
  CHECK(m_hi / m_lo == doctest::Approx(900.0 * 100.0).epsilon(1e-9));
  CHECK(c_hi / c_lo == doctest::Approx(900.0 * 90.0).epsilon(1e-9));
  const double start_mass = start.parameter(test::parameter_index(start, "c.y.b.b"));
  const double at_10_hz = 30.0 / (two_pi * two_pi * 100.0);  // on the start's chamber
  CHECK(at_10_hz > 10.0 * start_mass);
  CHECK(at_10_hz < m_hi);
}

}  // namespace global_look_test
