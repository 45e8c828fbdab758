#include "runtime/report/axis_ticks.hpp"

#include <doctest/doctest.h>

#include <string>
#include <vector>

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
  CHECK(nice_step(0.031, 1) == doctest::Approx(0.02));
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
