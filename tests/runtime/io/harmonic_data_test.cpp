// Harmonic data import: unit conversion, storage/loss form, every malformed case located.
#include "runtime/io/harmonic_data.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/fit/objective.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

namespace harmonic_data_test {

using namespace rheo::runtime;

namespace {
std::string error_of(const std::string& text, const DataReading& reading = {}) {
  try {
    harmonic_data_from_table(parse_table("h.csv", text), reading);
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
  CHECK(d.amplitude[0] == doctest::Approx(0.2).scale(0.0));
  CHECK(d.frequency[0] == doctest::Approx(1.0));
  CHECK(d.stiffness[0] == doctest::Approx(1500.0));
  CHECK(d.phase[0] == doctest::Approx(0.1).scale(0.0));
}

TEST_CASE("storage and loss columns give stiffness and phase") {
  const auto d = harmonic_data_from_table(parse_table("h.csv", "amplitude [mm],frequency [Hz],storage [N/m],loss [N/m]\n1,2,3000,4000\n"));
  CHECK(d.stiffness[0] == doctest::Approx(5.0));
  CHECK(d.phase[0] == doctest::Approx(std::atan2(4.0, 3.0)).scale(0.0));
}

TEST_CASE("malformed harmonic tables are located by file:row:column") {
  CHECK(error_of("amplitude [mm],stiffness [N/mm],phase [deg]\n1,2,3\n").find("need a column 'frequency'") != std::string::npos);
  CHECK(error_of("amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n-1,2,3,4\n")
            .find("h.csv:2:1: error: amplitude must be positive, got -1 mm (column 'amplitude')") == 0);
  CHECK(error_of("amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n1,0,3,4\n").find("frequency must be positive") != std::string::npos);
  CHECK(error_of("amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n1,2,3,-90\n")
            .find("h.csv:2:7: error: phase must lie in (-90, 180] deg, got -90 deg; check the column's unit") == 0);
}

TEST_CASE("a phase <= 0 from noise on a nearly elastic point is kept, its damping term left out of eq. 5.1 and named") {
  const auto d = harmonic_data_from_table(
      parse_table("h.csv", "amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n1,2,3,-0.02\n1,3,3,0\n1,4,3,0.5\n"));
  REQUIRE(d.size() == 3);
  CHECK(damping_residual(0.01, d.phase[0]) == 0.0);
  CHECK(damping_residual(0.01, d.phase[1]) == 0.0);
  CHECK(damping_residual(0.01, d.phase[2]) ==
        doctest::Approx(std::sin(0.01) / std::sin(0.5 * std::numbers::pi / 180) - 1.0).epsilon(1e-15).scale(0.0));
  const auto notes = damping_left_out(d);
  REQUIRE(notes.size() == 2);
  CHECK(notes[0] ==
        "h.csv:2: phase -0.02 deg <= 0 (noise on a nearly elastic point): its damping term is left out of eq. 5.1, which divides by sin(phase)");
  CHECK(notes[1].rfind("h.csv:3: phase 0 deg <= 0", 0) == 0);
}

TEST_CASE("an optional weight column weighs points, a negative weight is located") {
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

namespace {
const char* kHeader = "amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg],weight [-]\n";
}  // namespace

TEST_CASE("repeated points: the mean complex stiffness, the mean weight, the first row, a note names the rows") {
  // Rows 3 and 5 repeat (0.5 mm, 10 Hz): K* = 100 and 100 i N/mm, mean 50 + 50 i.
  const auto d = harmonic_data_from_table(
      parse_table("h.csv", std::string(kHeader) + "1,10,120,8,1\n0.5,10,100,0,1\n1,20,118,9,1\n0.5,10,100,90,3\n"));
  REQUIRE(d.size() == 3);
  CHECK(d.rows == std::vector<int>{2, 3, 4});
  CHECK(d.amplitude[1] == 0.5);
  CHECK(d.frequency[1] == 10.0);
  CHECK(d.stiffness[1] == doctest::Approx(50.0 * std::sqrt(2.0)).epsilon(1e-14));
  CHECK(d.phase[1] == doctest::Approx(std::numbers::pi / 4).epsilon(1e-14).scale(0.0));
  CHECK(d.weight[1] == 2.0);
  CHECK(d.stiffness[2] == 118.0);  // the others as they were, in file order
  REQUIRE(d.notes.size() == 1);
  CHECK(d.notes[0] == "h.csv:3: rows 3 and 5 repeat (0.5 mm, 10 Hz): averaged into one point (mean storage and loss stiffness)");
}

TEST_CASE("repeated points: three repeats are one point, equal storage and loss average to themselves") {
  const auto d = harmonic_data_from_table(
      parse_table("h.csv", std::string(kHeader) + "0.2,1,200,10,1\n0.2,1,200,10,1\n0.1,1,50,5,1\n0.2,1,200,10,1\n"));
  REQUIRE(d.size() == 2);
  CHECK(d.rows == std::vector<int>{2, 4});
  CHECK(d.stiffness[0] == doctest::Approx(200.0).epsilon(1e-14));
  CHECK(d.phase[0] == doctest::Approx(10.0 * std::numbers::pi / 180.0).epsilon(1e-14).scale(0.0));
  REQUIRE(d.notes.size() == 1);
  CHECK(d.notes[0].find("h.csv:2: rows 2, 3 and 5 repeat (0.2 mm, 1 Hz)") == 0);
}

TEST_CASE("repeated points: within a relative 1e-9 of amplitude and frequency, not beyond") {
  // 1 + 5e-10 is within 1e-9 of 1; 1 + 2e-9 is not.
  const auto near = harmonic_data_from_table(parse_table("h.csv", std::string(kHeader) + "1,10,100,5,1\n1.0000000005,10.000000005,100,5,1\n"));
  CHECK(near.size() == 1);
  CHECK(near.notes.size() == 1);
  const auto amplitude_apart = harmonic_data_from_table(parse_table("h.csv", std::string(kHeader) + "1,10,100,5,1\n1.000000002,10,100,5,1\n"));
  CHECK(amplitude_apart.size() == 2);
  CHECK(amplitude_apart.notes.empty());
  const auto frequency_apart = harmonic_data_from_table(parse_table("h.csv", std::string(kHeader) + "1,10,100,5,1\n1,10.00000002,100,5,1\n"));
  CHECK(frequency_apart.size() == 2);
  CHECK(frequency_apart.notes.empty());
  // The same frequency at another amplitude is another point.
  CHECK(harmonic_data_from_table(parse_table("h.csv", std::string(kHeader) + "1,10,100,5,1\n2,10,100,5,1\n")).size() == 2);
}

TEST_CASE("repeated points under duplicates = error: the second row is the error, naming the first") {
  DataReading reading;
  reading.duplicates = rheo::lang::DuplicatePoints::error;
  CHECK(error_of("amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n1,2,3,4\n1,2,5,6\n", reading)
            .find("h.csv:3:1: error: duplicate point (1 mm, 2 Hz), first at row 2; remove one, or average them with duplicates = average "
                  "(column 'amplitude')") == 0);
  CHECK(error_of("amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n1,2,3,4\n1,3,3,4\n1,2.000000001,5,6\n", reading)
            .find("h.csv:4:1: error: duplicate point (1 mm, 2 Hz), first at row 2") == 0);
  CHECK(error_of("amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n1,2,3,4\n1,3,5,6\n", reading).empty());
}

TEST_CASE("repeated points whose complex stiffnesses cancel are an error naming the rows") {
  CHECK(error_of("amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n1,2,1e-10,89.9999999999\n1,2,1e-10,-89.9999999999\n")
            .find("h.csv:2:1: error: rows 2 and 3 repeat (1 mm, 2 Hz) and their complex stiffnesses cancel") == 0);
}

TEST_CASE("a preload column (mean displacement, or a strain with the height) gives each point its p, points at other preloads are not repeats") {
  const auto d = harmonic_data_from_table(parse_table(
      "h.csv",
      "amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg],Mean displacement [um]\n0.5,10,300,5,0\n0.5,10,320,5,2000\n0.5,10,330,5,-1500\n"));
  REQUIRE(d.size() == 3);
  CHECK(d.preload == std::vector<double>{0.0, 2.0, -1.5});
  CHECK(d.notes.empty());
  const auto none = harmonic_data_from_table(parse_table("h.csv", "amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n0.5,10,300,5\n"));
  CHECK(none.preload == std::vector<double>{0.0});
  DataReading geometry;
  geometry.columns.height = 10.0;
  const auto strain = harmonic_data_from_table(
      parse_table("h.csv", "amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg],preload [%]\n0.5,10,300,5,5\n0.5,10,300,5,5\n"), geometry);
  REQUIRE(strain.size() == 1);  // the same preload twice: one point
  CHECK(strain.preload[0] == doctest::Approx(0.5).scale(0.0));
  CHECK(error_of("amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg],preload [s]\n0.5,10,300,5,1\n").find("h.csv:1:") == 0);
}

}  // namespace harmonic_data_test
