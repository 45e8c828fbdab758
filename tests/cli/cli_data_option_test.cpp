// `--data` with a data line's settings (cli/data_option.cpp) through the real binary: a table
// with unusual column names is read as `columns` says, a name holding a comma is quoted, and a
// setting that does not check exits 2 naming --data.
#include "cli_support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

namespace cli_data_option_test {

using nlohmann::json;
using rheo::test::run_rheo;
namespace fs = std::filesystem;

namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A spring of 250 N/mm measured at three points, under names no reader knows.
fs::path unusual_table(const std::string& name) {
  const fs::path csv = rheo::test::scratch_directory("cli-data") / name;
  std::ofstream(csv, std::ios::binary) << "A [mm];f [Hz];K_meas [N/mm];ph [deg]\n0.1;1;250;0\n0.1;10;250;0\n0.5;1;250;0\n";
  return csv;
}

fs::path spring_model() {
  const fs::path file = rheo::test::scratch_directory("cli-data") / "spring.rheo";
  std::ofstream(file, std::ios::binary) << "model m { spring s (k = 100 N/mm in [1, 1000]) }\n";
  return file;
}

const std::string columns = R"(columns = "amplitude = A, frequency = f, stiffness = K_meas, phase = ph")";

}  // namespace

TEST_CASE("rheo fit --data 'FILE, columns = ...' reads a table with unusual names as the settings say") {
  const fs::path csv = unusual_table("unusual.csv");
  const auto plain = run_rheo(fmt::format("fit {} --data {}", spring_model().string(), csv.string()));
  CHECK(plain.code == 4);  // without the settings no column is found
  const auto r = run_rheo(fmt::format("fit {} --json --data '{}, {}'", spring_model().string(), csv.string(), columns));
  REQUIRE(r.code == 0);
  const json report = json::parse(r.out);
  CHECK(report["data"][0]["file"] == csv.string());
  CHECK(report["data"][0]["points"] == 3);
  CHECK(report["parameters"][0]["value"].get<double>() == doctest::Approx(250.0).epsilon(1e-6));
}

TEST_CASE("rheo fit --data: a file name holding a comma goes in double quotes") {
  const fs::path csv = unusual_table("run 3, cured.csv");
  const auto r = run_rheo(fmt::format("fit {} --json --data '\"{}\", {}, weight = 0.5'", spring_model().string(), csv.string(), columns));
  REQUIRE(r.code == 0);
  const json report = json::parse(r.out);
  CHECK(report["data"][0]["file"] == csv.string());
  CHECK(report["data"][0]["weight"] == 0.5);
}

TEST_CASE("rheo fit and report --data: a setting that does not check exits 2 naming --data and where") {
  const fs::path csv = unusual_table("unusual.csv");
  const auto wrong_key = run_rheo(fmt::format("fit {} --data '{}, colums = \"f = x\"'", spring_model().string(), csv.string()));
  CHECK(wrong_key.code == 2);
  CHECK(contains(wrong_key.err, fmt::format("--data '{}, colums", csv.string())));
  CHECK(contains(wrong_key.err, "unknown setting 'colums' for a data line"));
  CHECK(contains(wrong_key.err, "did you mean 'columns'"));
  CHECK(wrong_key.out.empty());
  const auto bad_value = run_rheo(fmt::format("report {} -o {} --data 'x.csv, area = 3 mm'", spring_model().string(),
                                              (rheo::test::scratch_directory("cli-data") / "r.html").string()));
  CHECK(bad_value.code == 2);
  CHECK(contains(bad_value.err, "--data 'x.csv, area = 3 mm'"));
  CHECK(contains(bad_value.err, "<command line>:1:15: error: area expects an area"));
}

TEST_CASE("rheo report --data 'FILE, columns = ...' compares the model with the table read as the settings say") {
  const fs::path csv = unusual_table("unusual.csv");
  const fs::path html = rheo::test::scratch_directory("cli-data") / "report.html";
  const auto r = run_rheo(fmt::format("report {} -o {} --data '{}, {}'", spring_model().string(), html.string(), csv.string(), columns));
  CHECK(r.code == 0);
  CHECK(fs::exists(html));
}

TEST_CASE("rheo fit: repeated points are averaged with a note in the report, --data 'FILE, duplicates = error' refuses them") {
  const fs::path csv = rheo::test::scratch_directory("cli-data") / "repeated.csv";
  std::ofstream(csv, std::ios::binary) << "amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n0.5,10,250,0\n1,10,250,0\n0.5,10,250,0\n";
  const auto r = run_rheo(fmt::format("fit {} --data {}", spring_model().string(), csv.string()));
  REQUIRE(r.code == 0);
  CHECK(contains(r.out, fmt::format("  {}:2: rows 2 and 4 repeat (0.5 mm, 10 Hz): averaged into one point", csv.string())));
  CHECK(contains(r.out, "2 points"));
  const auto json_run = run_rheo(fmt::format("fit {} --json --data {}", spring_model().string(), csv.string()));
  REQUIRE(json_run.code == 0);
  CHECK(contains(json::parse(json_run.out)["notes"].dump(), "rows 2 and 4 repeat"));
  const auto refused = run_rheo(fmt::format("fit {} --data '{}, duplicates = error'", spring_model().string(), csv.string()));
  CHECK(refused.code == 4);
  CHECK(contains(refused.err, fmt::format("{}:4:1: error: duplicate point (0.5 mm, 10 Hz), first at row 2", csv.string())));
  const auto unknown = run_rheo(fmt::format("fit {} --data '{}, duplicates = sum'", spring_model().string(), csv.string()));
  CHECK(unknown.code == 2);
  CHECK(contains(unknown.err, "duplicates"));
}

}  // namespace cli_data_option_test
