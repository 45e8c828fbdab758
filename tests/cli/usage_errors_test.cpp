// cli/usage_errors.cpp through the binary: a command-line mistake is written as
// `rheo: error: ...` (docs/errors.md#usage-errors), exits 2 and names the nearest command,
// option or protocol to a misspelt one; --help and --version still exit 0.
#include "cli_support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <string>

namespace usage_errors_test {

using rheo::test::run_rheo;

namespace {

std::string example(const std::string& name) { return fmt::format("{}/{}", RHEO_EXAMPLES_DIR, name); }

// A usage error: exit 2, one message in rheo's format and nothing of CLI11's own wording.
void check_usage_error(const rheo::test::BinaryRun& r, const std::string& expected) {
  CAPTURE(r.err);
  CHECK(r.code == 2);
  CHECK(r.err.starts_with("rheo: error: "));
  CHECK(r.err.find(expected) != std::string::npos);
  CHECK(r.err.find("Run with --help") == std::string::npos);
  CHECK(r.err.find("A subcommand is required") == std::string::npos);
  CHECK(r.err.find("was not expected") == std::string::npos);
}

}  // namespace

TEST_CASE("a misspelt command names the nearest one") {
  check_usage_error(run_rheo("simulat " + example("bushing_d.rheo")), "unknown command 'simulat'; did you mean 'simulate'?");
  check_usage_error(run_rheo("frobnicate x.rheo"), "unknown command 'frobnicate'; the commands are check, simulate, fit");
  check_usage_error(run_rheo(""), "no command given");
}

TEST_CASE("an unknown option names the nearest option of its command") {
  check_usage_error(run_rheo("simulate " + example("bushing_d.rheo") + " --protocl harmonic"),
                    "unknown option '--protocl' for rheo simulate; did you mean '--protocol'?");
  check_usage_error(run_rheo("fit " + example("bushing_d.rheo") + " --max-evaluation=5"),
                    "unknown option '--max-evaluation' for rheo fit; did you mean '--max-evaluations'?");
  check_usage_error(run_rheo("--verison"), "unknown option '--verison' for rheo; did you mean '--version'?");
}

TEST_CASE("other command-line mistakes are usage errors in rheo's format, naming the command's help") {
  check_usage_error(run_rheo("simulate"), "see 'rheo simulate --help'");
  check_usage_error(run_rheo("simulate " + example("bushing_d.rheo") + " --threads -1"), "--threads");
  check_usage_error(run_rheo("check a.rheo b.rheo"), "b.rheo");
}

TEST_CASE("--help and --version are no errors") {
  for (const char* arguments : {"--help", "simulate --help", "--version", "fit -h"}) {
    CAPTURE(arguments);
    const auto r = run_rheo(arguments);
    CHECK(r.code == 0);
    CHECK(r.err.empty());
    CHECK_FALSE(r.out.empty());
  }
}

TEST_CASE("an unknown --protocol names the nearest protocol, one the file lacks names those it has") {
  check_usage_error(run_rheo("simulate " + example("bushing_d.rheo") + " --protocol harmonik"),
                    "unknown protocol 'harmonik' for --protocol; did you mean 'harmonic'?");
  check_usage_error(run_rheo("simulate " + example("bushing_d.rheo") + " --protocol step"), "has no step protocol; its protocols are harmonic");
  check_usage_error(run_rheo("simulate " + example("bushing_d.rheo") + " --model bushing_e"), "did you mean");
}

}  // namespace usage_errors_test
