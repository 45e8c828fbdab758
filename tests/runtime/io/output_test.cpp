#include "runtime/io/output.hpp"

#include "runtime/core/errors.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <numbers>
#include <fstream>
#include <sstream>

namespace output_test {

using namespace rheo::runtime;
namespace fs = std::filesystem;

TEST_CASE("harmonic CSV starts with the data files' four columns") {
  HarmonicPoint p;
  p.amplitude = 0.2, p.frequency = 3, p.measures.stiffness = 1420.5, p.measures.phase = 0.31, p.cycles = 1, p.converged = true;
  const std::string csv = harmonic_csv({"m", "m.rheo", "harmonic"}, {p}, HarmonicDefinition::thesis);
  CHECK(csv.find("\namplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg],") != std::string::npos);
  CHECK(csv.find("\n0.2,3,1420.5,17.76169") != std::string::npos);
}

TEST_CASE("harmonic CSV writes amplitude and frequency with 6 significant digits, more only to keep points apart") {
  HarmonicPoint p;
  p.measures.stiffness = 100, p.cycles = 1, p.converged = true;
  // 10 rad/s and 0.1 mm + a sum's rounding, as `frequency = 10 rad/s`, `0.1 mm .. 0.3 mm step 0.1 mm` make them.
  p.amplitude = 0.1 + 0.2, p.frequency = 10.0 / (2.0 * std::numbers::pi);
  CHECK(harmonic_csv({"m", "m.rheo", "harmonic"}, {p}, HarmonicDefinition::thesis).find("\n0.3,1.59155,100,") != std::string::npos);
  // Points 1e-6 apart stay apart (a result can be fitted later): that column gets the digits it needs.
  HarmonicPoint q = p;
  p.frequency = 1000000, q.frequency = 1000001;
  const std::string csv = harmonic_csv({"m", "m.rheo", "harmonic"}, {p, q}, HarmonicDefinition::thesis);
  CHECK(csv.find("\n0.3,1000000,100,") != std::string::npos);
  CHECK(csv.find("\n0.3,1000001,100,") != std::string::npos);
}

TEST_CASE("history numbers are short where the double is: 1e-04 s as 0.0001, 2 mm as 2, -0 as -0") {
  History h;
  h.time = {0.0001, 1e-05, 1e16}, h.displacement = {2.0, 0.1 + 0.2, -0.0}, h.force = {1e15, 7.8475241592896845, 5e-324};
  const std::string text = history_csv({"m", "m.rheo", "history"}, h);
  CHECK(text.find("\n0.0001,2,1000000000000000\n1e-05,0.30000000000000004,7.8475241592896845\n1e+16,-0,5e-324\n") != std::string::npos);
}

}  // namespace output_test
