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

using rheo::cli::Progress;

TEST_CASE("durations are said in seconds, minutes or hours") {
  CHECK(rheo::cli::rough_duration(0.4) == "0 s");
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
