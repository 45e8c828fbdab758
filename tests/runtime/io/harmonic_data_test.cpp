// Harmonic data import: unit conversion, storage/loss form, every malformed case located.
#include "runtime/io/harmonic_data.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/fit/objective.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

using namespace rheo::runtime;

namespace {
std::string error_of(const std::string& text) {
  try {
    harmonic_data_from_table(parse_table("h.csv", text));
  } catch (const DataError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("units convert: um, rad/s, kN/mm, rad") {
  const auto d = harmonic_data_from_table(
      parse_table("h.csv", "amplitude [um],frequency [rad/s],stiffness [kN/mm],phase [rad]\n200,6.283185307179586,1.5,0.1\n"));
  REQUIRE(d.size() == 1);
  CHECK(d.amplitude[0] == doctest::Approx(0.2));
  CHECK(d.frequency[0] == doctest::Approx(1.0));
  CHECK(d.stiffness[0] == doctest::Approx(1500.0));
  CHECK(d.phase[0] == doctest::Approx(0.1));
}

TEST_CASE("storage and loss columns give stiffness and phase") {
  const auto d = harmonic_data_from_table(parse_table("h.csv", "amplitude [mm],frequency [Hz],storage [N/m],loss [N/m]\n1,2,3000,4000\n"));
  CHECK(d.stiffness[0] == doctest::Approx(5.0));
  CHECK(d.phase[0] == doctest::Approx(std::atan2(4.0, 3.0)));
}

TEST_CASE("malformed harmonic tables are located by file:row:column") {
  CHECK(error_of("amplitude [mm],stiffness [N/mm],phase [deg]\n1,2,3\n").find("need a column 'frequency'") != std::string::npos);
  CHECK(error_of("amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n-1,2,3,4\n")
            .find("h.csv:2:1: error: amplitude must be positive, got -1 mm (column 'amplitude')") == 0);
  CHECK(error_of("amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n1,2,3,4\n1,2,5,6\n")
            .find("h.csv:3:1: error: duplicate point (1 mm, 2 Hz), first at row 2") == 0);
  CHECK(error_of("amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n1,0,3,4\n").find("frequency must be positive") != std::string::npos);
  CHECK(error_of("amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n1,2,3,-90\n")
            .find("h.csv:2:7: error: phase must lie in (-90, 90] deg, got -90 deg; check the column's unit") == 0);
}

TEST_CASE("a phase <= 0 from noise on a nearly elastic point is kept, its damping term left out of eq. 5.1 and named") {
  const auto d = harmonic_data_from_table(
      parse_table("h.csv", "amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n1,2,3,-0.02\n1,3,3,0\n1,4,3,0.5\n"));
  REQUIRE(d.size() == 3);
  CHECK(damping_residual(0.01, d.phase[0]) == 0.0);
  CHECK(damping_residual(0.01, d.phase[1]) == 0.0);
  CHECK(damping_residual(0.01, d.phase[2]) == doctest::Approx(std::sin(0.01) / std::sin(0.5 * std::numbers::pi / 180) - 1.0).epsilon(1e-15));
  const auto notes = damping_left_out(d);
  REQUIRE(notes.size() == 2);
  CHECK(notes[0] ==
        "h.csv:2: phase -0.02 deg <= 0 (noise on a nearly elastic point): its damping term is left out of eq. 5.1, which divides by sin(phase)");
  CHECK(notes[1].rfind("h.csv:3: phase 0 deg <= 0", 0) == 0);
}

TEST_CASE("an optional weight column weighs points; a negative weight is located") {
  const auto d = harmonic_data_from_table(
      parse_table("h.csv", "amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg],weight [-]\n1,2,3,4,0.5\n1,3,3,4,2\n"));
  REQUIRE(d.weight.size() == 2);
  CHECK(d.weight[0] == 0.5);
  CHECK(d.weight[1] == 2.0);
  CHECK(harmonic_data_from_table(parse_table("h.csv", "amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n1,2,3,4\n")).weight ==
        std::vector<double>{1.0});
  CHECK(error_of("amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg],weight [-]\n1,2,3,4,-1\n")
            .find("h.csv:2:9: error: a point's weight must be >= 0") == 0);
}
