// `rheo fit` with a load-cell offset on a history's data line (#25 item 2) through the real
// binary: the fitted offset in the text and JSON reports, written into the fitted file's data
// line (which then fits the same as a declared offset), and named in its header for --data.
#include "lang/frontend.hpp"
#include "cli_support.hpp"
#include "support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace cli_force_offset_test {

using namespace rheo;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

using Run = test::BinaryRun;

fs::path scratch() { return test::scratch_directory("cli-offset"); }

std::string read_text(const fs::path& path) { return test::read_file(path.string()); }

void write_text(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

Run run(const std::string& arguments) { return test::run_rheo(arguments); }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// F = 80 N/mm u + 40 N and a small deterministic ripple, so that the offset has a standard error.
fs::path rig_data() {
  const fs::path csv = scratch() / "rig.csv";
  std::string text = "time [s],displacement [mm],force [N]\n";
  for (int j = 0; j < 200; ++j) {
    const double u = 0.5 + std::sin(0.05 * j);
    text += fmt::format("{},{:.17g},{:.17g}\n", 0.01 * j, u, 80.0 * u + 40.0 + 0.2 * std::sin(7.3 * j));
  }
  write_text(csv, text);
  return csv;
}

const char* kModel = "# a spring\nmodel s {\n  spring e (k = 10 N/mm in [1, 1000])\n}\n";

}  // namespace

TEST_CASE("a fitted force offset: reported with its standard error, written into the fitted data line, reused as declared") {
  const std::string csv = rig_data().string();
  const fs::path file = scratch() / "offset.rheo";
  write_text(file, std::string(kModel) + "fit {\n  data \"rig.csv\", force_offset = free  # the load cell's zero\n}\n");
  const fs::path fitted = scratch() / "offset_fitted.rheo";
  const Run text = run(fmt::format("fit {} -o {}", file.string(), fitted.string()));
  REQUIRE(text.code == 0);
  CHECK(contains(text.out, fmt::format("data {} (history, 200 samples, weight 1, force offset fitted)", csv)));
  CHECK(contains(text.out, fmt::format("data {}: force_offset", csv)));

  const Run j = run(fmt::format("fit {} --json", file.string()));
  REQUIRE(j.code == 0);
  const json report = json::parse(j.out);
  const json& offset = report["data"][0]["force_offset"];
  CHECK(offset["free"] == true);
  CHECK(offset["unit"] == "N");
  CHECK(offset["value"].get<double>() == doctest::Approx(40.0).epsilon(1e-2));
  CHECK(offset["standard_error"].get<double>() > 0.0);
  CHECK(offset["standard_error"].get<double>() < 0.1);
  CHECK(offset["identifiable"] == true);
  CHECK(offset["correlation"].size() == 1);

  // The fitted file declares the fitted value; fitting it again keeps it and ends where the free fit did.
  const std::string written = read_text(fitted);
  CHECK(contains(written, "data \"rig.csv\", force_offset = "));
  CHECK_FALSE(contains(written, "force_offset = free"));
  CHECK(contains(written, " N  # the load cell's zero"));
  const lang::Program program = lang::load_program(fitted.string());
  REQUIRE(program.fits.size() == 1);
  const auto& declared = program.fits[0].data.at(0).force_offset;
  CHECK_FALSE(declared.free);
  CHECK(declared.value == doctest::Approx(offset["value"].get<double>()).epsilon(1e-12));
  const Run again = run(fmt::format("fit {} --json", fitted.string()));
  REQUIRE(again.code == 0);
  const json refit = json::parse(again.out);
  CHECK(refit["data"][0]["force_offset"]["free"] == false);
  CHECK(refit["data"][0]["err"].get<double>() == doctest::Approx(report["data"][0]["err"].get<double>()).epsilon(1e-9).scale(0.0));
}

TEST_CASE("--data with force_offset = free: the fitted file's header says how to reuse the offset") {
  const fs::path csv = rig_data();
  const fs::path file = scratch() / "plain.rheo";
  write_text(file, kModel);
  const fs::path fitted = scratch() / "plain_fitted.rheo";
  const Run r = run(fmt::format("fit {} --data '{}, force_offset = free' -o {}", file.string(), csv.string(), fitted.string()));
  REQUIRE(r.code == 0);
  CHECK(contains(read_text(fitted), "on its data line to reuse it"));
  const Run wrong = run(fmt::format("fit {} --data '{}, force_offset = 40'", file.string(), csv.string()));
  CHECK(wrong.code == 2);
  CHECK(contains(wrong.err, "force_offset needs a force unit"));
}

}  // namespace cli_force_offset_test
