#include "runtime/output.hpp"

#include "runtime/errors.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace rheo::runtime;
namespace fs = std::filesystem;

TEST_CASE("harmonic CSV starts with the data files' four columns") {
  HarmonicPoint p;
  p.amplitude = 0.2, p.frequency = 3, p.measures.stiffness = 1420.5, p.measures.phase = 0.31, p.cycles = 1, p.converged = true;
  const std::string csv = harmonic_csv({"m", "m.rheo", "harmonic"}, {p}, HarmonicDefinition::thesis);
  CHECK(csv.find("\namplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg],") != std::string::npos);
  CHECK(csv.find("\n0.2,3,1420.5,17.76169") != std::string::npos);
  // Amplitude and frequency are written so that they read back exactly (a result can be fitted
  // later: points 1e-7 apart stay apart).
  p.amplitude = 0.12345678901234, p.frequency = 1000001;
  CHECK(harmonic_csv({"m", "m.rheo", "harmonic"}, {p}, HarmonicDefinition::thesis).find("\n0.12345678901234,1000001,") != std::string::npos);
}

TEST_CASE("outputs are written atomically and a failed write leaves the old file intact") {
  const fs::path dir = fs::temp_directory_path() / fmt::format("rheo-output-{}", ::getpid());
  fs::create_directories(dir);
  const fs::path target = dir / "out.csv";
  write_output(target.string(), "first\n");
  write_output(target.string(), "second\n");
  std::ifstream in(target);
  std::stringstream s;
  s << in.rdbuf();
  CHECK(s.str() == "second\n");
  CHECK_THROWS_AS(write_output((dir / "missing" / "out.csv").string(), "x"), DataError);
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  CHECK(files == 1);  // no temporary left behind
  fs::remove_all(dir);
}

TEST_CASE("writing to a device writes through it and leaves it a device") {
  write_output("/dev/null", "discarded\n");
  CHECK(fs::is_character_file("/dev/null"));
}
