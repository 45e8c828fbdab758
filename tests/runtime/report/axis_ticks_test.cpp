#include "runtime/report/axis_ticks.hpp"

#include <doctest/doctest.h>

#include <string>
#include <vector>

namespace axis_ticks_test {

using namespace rheo::runtime::report;

namespace {
std::vector<std::string> labels(const std::vector<Tick>& ticks) {
  std::vector<std::string> out;
  for (const Tick& t : ticks) out.push_back(t.label);
  return out;
}
}  // namespace

TEST_CASE("report axis ticks: linear ticks are 1-2-5 steps with clean labels") {
  CHECK(labels(linear_ticks(0.0, 1.0, 5)) == std::vector<std::string>{"0", "0.2", "0.4", "0.6", "0.8", "1"});
  CHECK(labels(linear_ticks(0.1, 0.7, 6)) == std::vector<std::string>{"0.1", "0.2", "0.3", "0.4", "0.5", "0.6", "0.7"});
  CHECK(labels(linear_ticks(-23.0, 47.0, 6)) == std::vector<std::string>{"-20", "-10", "0", "10", "20", "30", "40"});
  CHECK(labels(linear_ticks(1320.0, 1910.0, 6)) == std::vector<std::string>{"1400", "1500", "1600", "1700", "1800", "1900"});
  CHECK(nice_step(7.0, 1) == doctest::Approx(5.0));
  CHECK(nice_step(0.031, 1) == doctest::Approx(0.02).scale(0.0));
  for (const Tick& t : linear_ticks(0.95, 50.5, 6)) CHECK((t.value >= 0.95 && t.value <= 50.5));
}

TEST_CASE("report axis ticks: log ticks by decade, denser over short ranges") {
  CHECK(labels(log_ticks(0.05, 2000.0)) == std::vector<std::string>{"0.1", "1", "10", "100", "1000"});
  CHECK(labels(log_ticks(0.9, 110.0)) == std::vector<std::string>{"1", "2", "5", "10", "20", "50", "100"});
  CHECK(labels(log_ticks(0.18, 3.3)) == std::vector<std::string>{"0.2", "0.3", "0.5", "1", "2", "3"});
  CHECK(labels(log_ticks(1.0, 2.5)) == std::vector<std::string>{"1", "2"});
  // Too narrow for two mantissa ticks: linear ticks instead.
  CHECK(log_ticks(12.0, 15.0).size() >= 2);
}

namespace {
// The labelled ticks of a log axis over [lo, hi], and checks every log axis must pass: labels
// at most MAX, compact (no '+', no exponent with a leading zero), increasing values, and a grid
// line at every decade when they are thinned.
std::vector<std::string> checked_log_labels(double lo, double hi, int max = 8) {
  const std::vector<Tick> ticks = log_ticks(lo, hi, max);
  std::vector<std::string> out;
  for (std::size_t i = 0; i < ticks.size(); ++i) {
    CAPTURE(ticks[i].label);
    CHECK(ticks[i].value >= lo * (1 - 1e-9));
    CHECK(ticks[i].value <= hi * (1 + 1e-9));
    if (i > 0) CHECK(ticks[i].value > ticks[i - 1].value);
    CHECK(ticks[i].label.find('+') == std::string::npos);
    CHECK(ticks[i].label.find("e0") == std::string::npos);
    CHECK(ticks[i].label.find("e-0") == std::string::npos);
    CHECK(ticks[i].label.size() <= 5);
    if (!ticks[i].label.empty()) out.push_back(ticks[i].label);
  }
  CHECK(out.size() >= 2);
  CHECK(out.size() <= static_cast<std::size_t>(max));
  return out;
}
}  // namespace

TEST_CASE("report axis ticks: one decade gets mantissa ticks") {
  CHECK(checked_log_labels(1.0, 10.0) == std::vector<std::string>{"1", "2", "3", "5", "10"});
  CHECK(checked_log_labels(2e-6, 2e-5) == std::vector<std::string>{"2e-6", "3e-6", "5e-6", "1e-5", "2e-5"});
}

TEST_CASE("report axis ticks: three decades, every decade labelled") {
  CHECK(checked_log_labels(0.001, 1.0) == std::vector<std::string>{"0.001", "0.01", "0.1", "1"});
  CHECK(checked_log_labels(3e3, 4e6) == std::vector<std::string>{"1e4", "1e5", "1e6"});
}

TEST_CASE("report axis ticks: 18 decades, every third labelled, the others grid lines") {
  const std::vector<Tick> ticks = log_ticks(1e-9, 1e9);
  CHECK(ticks.size() == 19);  // a line at every decade
  CHECK(checked_log_labels(1e-9, 1e9) == std::vector<std::string>{"1e-9", "1e-6", "0.001", "1", "1000", "1e6", "1e9"});
  // At multiples of 3 also when the range does not start on one.
  CHECK(checked_log_labels(2e-8, 5e10) == std::vector<std::string>{"1e-6", "0.001", "1", "1000", "1e6", "1e9"});
}

TEST_CASE("report axis ticks: 30 decades (a master curve), every fifth labelled") {
  CHECK(checked_log_labels(1e-15, 1e15) == std::vector<std::string>{"1e-15", "1e-10", "1e-5", "1", "1e5", "1e10", "1e15"});
  CHECK(checked_log_labels(3e-15, 3e14) == std::vector<std::string>{"1e-10", "1e-5", "1", "1e5", "1e10"});
  CHECK(log_ticks(3e-15, 3e14).size() == 29);  // 1e-14 .. 1e14
  // A tighter budget thins further.
  CHECK(checked_log_labels(1e-15, 1e15, 4) == std::vector<std::string>{"1e-10", "1", "1e10"});
}

TEST_CASE("report axis ticks: compact numbers") {
  CHECK(compact_number(1e14) == "1e14");
  CHECK(compact_number(1e-14) == "1e-14");
  CHECK(compact_number(1.29568669751702e-09) == "1.3e-9");
  CHECK(compact_number(9.9996e5) == "1e6");
  CHECK(compact_number(1234.5) == "1230");
  CHECK(compact_number(0.0123456) == "0.0123");
  CHECK(compact_number(-2e-5) == "-2e-5");
  CHECK(compact_number(0.0) == "0");
}

TEST_CASE("report axis ticks: a linear axis keeps 1-2-5 steps, labels without exponent noise") {
  const std::vector<Tick> ticks = linear_ticks(-0.4, 2.9, 6);
  REQUIRE(ticks.size() >= 4);
  const double step = ticks[1].value - ticks[0].value;
  CHECK(step == doctest::Approx(0.5).scale(0.0));
  for (std::size_t i = 1; i < ticks.size(); ++i) CHECK(ticks[i].value - ticks[i - 1].value == doctest::Approx(step).scale(0.0));
  CHECK(labels(ticks) == std::vector<std::string>{"0", "0.5", "1", "1.5", "2", "2.5"});
  CHECK(labels(linear_ticks(0.0, 4e6, 4)).back() == "4e6");
}

}  // namespace axis_ticks_test
