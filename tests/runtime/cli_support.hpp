// Running the rheo binary (RHEO_BINARY) from the tests: exit code, standard output and error.
#pragma once

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace rheo::test {

struct BinaryRun {
  int code = -1;  // the exit code; -1 when rheo did not exit (e.g. killed by a signal)
  std::string out, err;
};

// A scratch directory of this test process, named after NAME.
inline std::filesystem::path scratch_directory(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / fmt::format("rheo-{}-{}", name, ::getpid());
  std::filesystem::create_directories(dir);
  return dir;
}

// Runs `rheo ARGUMENTS` (a shell command line: quote what needs it).
inline BinaryRun run_rheo(const std::string& arguments) {
  const auto err = scratch_directory("run") / "stderr.txt";
  BinaryRun r;
  FILE* pipe = popen(fmt::format("{} {} 2> {}", RHEO_BINARY, arguments, err.string()).c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::array<char, 4096> buffer{};
  while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) r.out.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  r.err = text.str();
  return r;
}

}  // namespace rheo::test
