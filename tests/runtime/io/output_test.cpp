#include "runtime/io/output.hpp"

#include "runtime/core/errors.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <numbers>
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

TEST_CASE("writing to a symbolic link replaces the file it points to and keeps the link, through chains and to a new file") {
  const fs::path dir = fs::temp_directory_path() / fmt::format("rheo-output-link-{}", ::getpid());
  fs::create_directories(dir / "results");
  auto read = [](const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  std::ofstream(dir / "results" / "run.csv") << "old\n";
  fs::create_symlink("results/run.csv", dir / "latest.csv");  // relative to the link's directory
  fs::create_symlink(dir / "latest.csv", dir / "chain.csv");  // a link to a link, absolute
  write_output((dir / "latest.csv").string(), "new\n");
  CHECK(fs::is_symlink(fs::symlink_status(dir / "latest.csv")));
  CHECK(read(dir / "results" / "run.csv") == "new\n");
  write_output((dir / "chain.csv").string(), "newer\n");
  CHECK(fs::is_symlink(fs::symlink_status(dir / "chain.csv")));
  CHECK(fs::is_symlink(fs::symlink_status(dir / "latest.csv")));
  CHECK(read(dir / "results" / "run.csv") == "newer\n");
  fs::create_symlink("results/absent.csv", dir / "dangling.csv");
  write_output((dir / "dangling.csv").string(), "created\n");
  CHECK(fs::is_symlink(fs::symlink_status(dir / "dangling.csv")));
  CHECK(read(dir / "results" / "absent.csv") == "created\n");
  fs::create_symlink("loop_b.csv", dir / "loop_a.csv");
  fs::create_symlink("loop_a.csv", dir / "loop_b.csv");
  CHECK_THROWS_WITH_AS(write_output((dir / "loop_a.csv").string(), "x"), doctest::Contains("too many levels of links"), DataError);
  fs::remove_all(dir);
}

TEST_CASE("history numbers are short where the double is: 1e-04 s as 0.0001, 2 mm as 2, -0 as -0") {
  History h;
  h.time = {0.0001, 1e-05, 1e16}, h.displacement = {2.0, 0.1 + 0.2, -0.0}, h.force = {1e15, 7.8475241592896845, 5e-324};
  const std::string text = history_csv({"m", "m.rheo", "history"}, h);
  CHECK(text.find("\n0.0001,2,1000000000000000\n1e-05,0.30000000000000004,7.8475241592896845\n1e+16,-0,5e-324\n") != std::string::npos);
}
