// Running the rheo binary (RHEO_BINARY) from the tests: exit code, standard output and error.
#pragma once

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>

namespace rheo::test {

// The bytes of a file the test needs (a document, an output); the test fails where it cannot be read.
inline std::string read_required(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE_MESSAGE(in, "cannot read " << path.string());
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// True under CI (.ci/run exports CI=true): there every tool a test needs must be installed.
inline bool in_ci() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && std::string_view(ci) == "true";
}

// Whether `tool` (a name looked up on PATH, or an absolute path) is installed. When it is not, a
// test that needs it fails under CI, naming the Debian package, and outside CI says that it
// is skipped (the caller then returns).
inline bool tool_installed(const std::string& tool, const std::string& debian_package) {
  const std::string probe = tool.starts_with('/') ? "test -x '" + tool + "'" : "command -v '" + tool + "' >/dev/null";
  if (std::system(probe.c_str()) == 0) return true;
  const std::string advice = fmt::format("{} is not installed (Debian package {}; .ci/install-deps installs it)", tool, debian_package);
  if (in_ci()) {
    FAIL_CHECK(advice << ": CI needs it");
  } else {
    MESSAGE("SKIPPED: " << advice);
  }
  return false;
}

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

// Runs `rheo ARGUMENTS` (a shell command line: quote what needs it), with the environment
// assignments `environment` (e.g. "PATH=/nonexistent") in front when given.
inline BinaryRun run_rheo(const std::string& arguments, const std::string& environment = "") {
  const auto err = scratch_directory("run") / "stderr.txt";
  BinaryRun r;
  FILE* pipe = popen(fmt::format("{} {} {} 2> {}", environment, RHEO_BINARY, arguments, err.string()).c_str(), "r");
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
