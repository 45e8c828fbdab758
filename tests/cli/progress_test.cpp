// The progress lines of long runs (cli/progress.hpp): a streamed history's line with the time
// left at its pace so far, and the durations it is said in.
#include "cli/progress.hpp"

#include <doctest/doctest.h>

#include <cstdlib>
#include <iostream>
#include <regex>
#include <string>
#include <sstream>
#include <thread>

namespace progress_test {

using rheo::cli::Progress;

TEST_CASE("durations are said in microseconds, milliseconds, seconds, minutes or hours") {
  CHECK(rheo::cli::rough_duration(4.2e-5) == "42 us");
  CHECK(rheo::cli::rough_duration(7.1e-4) == "710 us");
  CHECK(rheo::cli::rough_duration(1.46e-3) == "1.5 ms");
  CHECK(rheo::cli::rough_duration(0.4) == "400 ms");
  CHECK(rheo::cli::rough_duration(1.4) == "1 s");
  CHECK(rheo::cli::rough_duration(119.0) == "119 s");
  CHECK(rheo::cli::rough_duration(150.0) == "2 min");
  CHECK(rheo::cli::rough_duration(7000.0) == "117 min");
  CHECK(rheo::cli::rough_duration(3.5 * 3600.0) == "3.5 h");
}

TEST_CASE("a progress line says the time left at its pace so far") {
  std::ostringstream captured;
  std::streambuf* const original = std::cerr.rdbuf(captured.rdbuf());
  const auto progress = Progress::start(true, std::nullopt);  // --progress: a line a second at most
  progress->label("history of model h");
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  // A quarter done after about 1.1 s: three quarters left at that pace, about 3.3 s (no quiet
  // start: stream_callback's lines wait 3 s).
  progress->status("400 samples, 25 % of the file read", 0.0, 0.25);
  std::cerr.rdbuf(original);
  const std::string line = captured.str();
  INFO(line);
  std::smatch m;
  REQUIRE(std::regex_match(line, m, std::regex(R"(rheo: history of model h: 400 samples, 25 % of the file read, (\d+) s, about (\d+) s left\n)")));
  const int clock = std::stoi(m[1].str()), left = std::stoi(m[2].str());
  CHECK(clock >= 1);
  CHECK(std::abs(left - 3 * clock) <= 2);  // each figure rounded to the second
}

TEST_CASE("a fit's progress says what its budget allows, and announces it at the start where that is long") {
  std::ostringstream captured;
  std::streambuf* const original = std::cerr.rdbuf(captured.rdbuf());
  {
    const auto progress = Progress::start(true, std::nullopt);
    progress->label("fit m");
    progress->announce_budget();
    progress->evaluation({1, 0.5, "start", 20000, 1.5e-3});   // 19999 more at 1.5 ms: 30 s, announced
    progress->evaluation({2, 0.4, "sample", 20000, 3.0e-3});  // within the second: no line
    progress->stage("fit m");                                 // --progress: a line at the stage's first evaluation
    progress->evaluation({100, 0.25, "local", 20000, 0.15});  // 19900 more at 1.5 ms
  }
  {
    const auto progress = Progress::start(true, std::nullopt);
    progress->label("fit small");
    progress->announce_budget();
    progress->evaluation({1, 0.5, "start", 100, 1e-3});  // 0.1 s allowed: nothing said
  }
  std::cerr.rdbuf(original);
  CHECK(captured.str() ==
        "rheo: fit m: an evaluation takes about 1.5 ms, so its budget of 20000 evaluations allows up to about 30 s; --time-limit or "
        "--max-evaluations bound it\n"
        "rheo: fit m\n"
        "rheo: fit m: 100 evaluations, best objective 0.25 (local), 0 s; the budget allows 30 s more\n");
}

}  // namespace progress_test
