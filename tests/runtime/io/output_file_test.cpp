// Outputs written so that no half-written file remains: whole contents (write_output) and
// outputs made as they run (PendingOutput), through links, to devices and to standard output.
#include "runtime/io/output_file.hpp"

#include "runtime/core/errors.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace output_file_test {

using namespace rheo::runtime;
namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t files_in(const fs::path& dir) {
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  return files;
}

}  // namespace

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

TEST_CASE("a pending output is in place only once committed, and leaves nothing behind when abandoned") {
  const fs::path dir = fs::temp_directory_path() / fmt::format("rheo-pending-{}", ::getpid());
  fs::create_directories(dir);
  const fs::path target = dir / "out.csv";
  std::ofstream(target) << "earlier result\n";
  {
    PendingOutput out(target.string());
    out.write("half a ");
    CHECK(read(target) == "earlier result\n");             // untouched while the run goes on
    for (const auto& entry : fs::directory_iterator(dir))  // the temporary is unnamed (O_TMPFILE) or a hidden sibling
      if (entry.path() != target) CHECK(entry.path().filename().string().starts_with(".out.csv.rheo-tmp-"));
  }
  CHECK(read(target) == "earlier result\n");
  CHECK(files_in(dir) == 1);
  {
    PendingOutput out(target.string());
    out.write("discarded");
    out.restart();
    out.write("time [s]\n");
    out.write("0\n");
    out.commit();
  }
  CHECK(read(target) == "time [s]\n0\n");
  CHECK(files_in(dir) == 1);
  // Two pending outputs of one file (two protocols naming it): the last committed wins.
  PendingOutput first(target.string()), second(target.string());
  first.write("first\n"), second.write("second\n");
  first.commit(), second.commit();
  CHECK(read(target) == "second\n");
  CHECK(files_in(dir) == 1);
  CHECK_THROWS_WITH_AS(PendingOutput((dir / "missing" / "out.csv").string()), doctest::Contains("does not exist"), DataError);
  fs::remove_all(dir);
}

TEST_CASE("a pending output to a device is spooled and copied there at commit, and the device stays a device") {
  PendingOutput out("/dev/null");
  out.write("discarded\n");
  out.commit();
  CHECK(fs::is_character_file("/dev/null"));
}

TEST_CASE("a pending output falls back cleanly where the system has no O_TMPFILE or no /proc to name an unnamed file") {
  const fs::path dir = fs::temp_directory_path() / fmt::format("rheo-pending-fallback-{}", ::getpid());
  fs::create_directories(dir);
  const fs::path target = dir / "out.csv";
  // More than copy_all's 64 KiB chunk, so that a copy takes several rounds.
  std::string content;
  for (int i = 0; content.size() < 200000; ++i) content += fmt::format("{},{}\n", i, 0.5 * i);
  for (const auto route : {PendingOutput::Temporary::unnamed_copied_at_commit, PendingOutput::Temporary::named_sibling}) {
    CAPTURE(static_cast<int>(route));
    std::ofstream(target) << "earlier result\n";
    {
      PendingOutput out(target.string(), route);
      out.write(content);
      CHECK(read(target) == "earlier result\n");
      // Unnamed until commit where it can be; the named fallback is a hidden sibling.
      CHECK(files_in(dir) == (route == PendingOutput::Temporary::named_sibling ? 2u : 1u));
    }
    CHECK(read(target) == "earlier result\n");  // abandoned: nothing behind
    CHECK(files_in(dir) == 1);
    {
      PendingOutput out(target.string(), route);
      out.write("discarded");
      out.restart();
      out.write(content.substr(0, 100000));
      out.write(content.substr(100000));
      out.commit();
    }
    CHECK(read(target) == content);
    CHECK(files_in(dir) == 1);
  }
  fs::remove_all(dir);
}

}  // namespace output_file_test
