// `rheo diagnose` and `rheo refine` through the real binary (cli/diagnose_command.cpp):
// a linear spring with one friction element against specimen D's static loops
// (examples/data/specimen_D_static.csv), whose stiffening the linear spring cannot follow.
// Exit codes as docs/errors.md lists them.
#include "cli_support.hpp"
#include "report_support.hpp"
#include "support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace cli_diagnose_test {

using rheo::test::count;
using rheo::test::run_rheo;
namespace fs = std::filesystem;

namespace {

// The model file, in a scratch directory, with a fit block naming the static loops.
fs::path linear_model(const fs::path& dir) {
  const fs::path file = dir / "linear.rheo";
  std::ofstream(file) << "model linear {\n"
                         "  spring   k0 (k = 300 N/mm in [10, 10000])\n"
                         "  friction f1 (k = 200 N/mm in [1, 10000], uy = 100 um in [0.1, 10000])\n"
                         "}\n"
                      << fmt::format("fit linear {{\n  data \"{}/specimen_D_static.csv\"\n}}\n", RHEO_DATA_DIR);
  return file;
}

}  // namespace

TEST_CASE("rheo diagnose: names the stiffening, writes the refined model, the JSON summary, the report and the plot") {
  const fs::path dir = rheo::test::scratch_directory("diagnose");
  const fs::path model = linear_model(dir), refined = dir / "refined.rheo", html = dir / "diagnose.html", svg = dir / "loop.svg";
  const auto r = run_rheo(
      fmt::format("diagnose {} --json -o {} --report {} --plot {}", model.string(), refined.string(), html.string(), svg.string()));
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"effect", "evidence", "err_before", "err_after", "added", "model"}) CHECK(j.contains(key));
  CHECK(j["effect"] == "nonlinear-elasticity");
  CHECK(j["gap_measure"] == "RMS force residual");
  CHECK(j["err_after"].get<double>() <= j["err_before"].get<double>() / 3.0);
  CHECK(j["added"].size() == 1);
  CHECK(j["output"] == refined.string());
  // The refined file is what the JSON carries, and it checks.
  CHECK(rheo::test::read_file(refined.string()) == j["model"].get<std::string>());
  CHECK(run_rheo(fmt::format("check {}", refined.string())).code == 0);
  // The report: the loops of the refined model and of the model before, and the diagnosis.
  const std::string page = rheo::test::read_file(html.string());
  CHECK(page.find("<h1>rheo diagnose: model linear</h1>") != std::string::npos);
  CHECK(page.find("<section id=\"diagnosis\">") != std::string::npos);
  CHECK(count(page, "data-figure=\"hysteresis\"") == 1);
  CHECK(count(page, "data-style=\"dashed\"") == 1);
  CHECK(count(page, "data-figure=\"network-before\"") == 1);
  const std::string figure = rheo::test::read_file(svg.string());
  CHECK(figure.starts_with("<?xml"));
  CHECK(count(figure, "class=\"series\"") == 3);  // measured, model before, model refined
  CHECK(r.err.find("report written to") != std::string::npos);
}

TEST_CASE("rheo refine: rounds until none, each printed with its gap, the final model and report written") {
  const fs::path dir = rheo::test::scratch_directory("refine");
  const fs::path model = linear_model(dir), html = dir / "refine.html";
  // Without -o the final model goes beside the file, as FILE_refined.rheo.
  const auto r = run_rheo(fmt::format("refine {} --rounds 3 --report {}", model.string(), html.string()));
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("round 1: RMS force residual = ") != std::string::npos);
  CHECK(r.out.find("effect nonlinear-elasticity, added 'k0'") != std::string::npos);
  // Round 2 starts from the yeoh that replaced k0 (its parameters are the free ones now).
  CHECK(r.out.find("round 2: ") != std::string::npos);
  CHECK(r.out.find("effect none") != std::string::npos);
  const fs::path final_model = dir / "linear_refined.rheo";
  REQUIRE(fs::exists(final_model));
  CHECK(rheo::test::read_file(final_model.string()).find("yeoh k0") != std::string::npos);
  const std::string page = rheo::test::read_file(html.string());
  CHECK(page.find("<h2>Refinement</h2>") != std::string::npos);
  CHECK(page.find("<h3>Round 2: none</h3>") != std::string::npos);
}

TEST_CASE("rheo diagnose: usage and data errors exit 2 and 4 before any fit, and write nothing") {
  const fs::path dir = rheo::test::scratch_directory("diagnose-errors");
  const fs::path model = linear_model(dir), refined = dir / "never.rheo";
  const auto block = run_rheo(fmt::format("diagnose {} --block 2 -o {}", model.string(), refined.string()));
  CHECK(block.code == 2);
  CHECK(block.err.find("fit block") != std::string::npos);
  const auto missing = run_rheo(fmt::format("diagnose {} --data {} -o {}", model.string(), (dir / "absent.csv").string(), refined.string()));
  CHECK(missing.code == 4);
  CHECK(missing.err.find("absent.csv") != std::string::npos);
  CHECK(!fs::exists(refined));
  // A PNG plot without rsvg-convert on PATH (rheo needs nothing else from it).
  const auto png = run_rheo(fmt::format("diagnose {} --plot {}", model.string(), (dir / "loop.png").string()), "PATH=/nonexistent");
  CHECK(png.code == 2);
  CHECK(png.err.find("librsvg2-bin") != std::string::npos);
  CHECK(png.err.find("fitting") == std::string::npos);  // refused before the first fit
}

TEST_CASE("rheo diagnose --time-limit stops in time with the results so far, and --progress writes progress lines to a pipe") {
  const fs::path dir = rheo::test::scratch_directory("diagnose-time");
  const fs::path model = linear_model(dir);
  // 1 ms: the model's fit is cut after its start, and nothing after it begins.
  const auto limited = run_rheo(fmt::format("diagnose {} --json --time-limit 1ms", model.string()));
  CAPTURE(limited.err);
  REQUIRE(limited.code == 0);
  const auto j = nlohmann::json::parse(limited.out);
  CHECK(j["time_limited"] == true);
  CHECK(j["added"].empty());
  CHECK(j["evidence"]["candidates"].empty());
  CHECK(limited.err.find("screening") == std::string::npos);
  const auto bad = run_rheo(fmt::format("refine {} --time-limit soon", model.string()));
  CHECK(bad.code == 2);
  CHECK(bad.err.find("--time-limit 'soon'") != std::string::npos);
  // Standard error is a pipe here: --progress still writes whole lines, one per stage at least.
  const auto progress = run_rheo(fmt::format("diagnose {} --json --progress", model.string()));
  REQUIRE(progress.code == 0);
  CHECK(progress.err.find("rheo: fitting model linear\n") != std::string::npos);
  CHECK(progress.err.find("rheo: fitting model linear\nrheo: fitting model linear: 1 evaluations") != std::string::npos);
  CHECK(progress.err.find("\r") == std::string::npos);
  CHECK(nlohmann::json::parse(progress.out)["evidence"].contains("noise"));
}

// The rig history with its load cell's 150 N zero (examples/data/README.md), fitted without the
// data line's force_offset: the preloaded yeoh takes up most of the constant as it is fitted, so
// the offset screens low, and only its refit shows it (#24 item 1, `offset`).
TEST_CASE("rheo refine: a load cell's zero no data line states is named offset, fitted to the 150 N it is, and the rounds end at none") {
  const fs::path dir = rheo::test::scratch_directory("refine-offset");
  const fs::path model = dir / "rig.rheo", final_model = dir / "rig_final.rheo";
  std::ofstream(model) << "model bushing {\n"
                          "  yeoh     rubber (D10 = 100 N/mm in [1, 10000], D20 = 0 N/mm^3 in [-100, 100], D30 = 0 N/mm^5 in [-10, 10])\n"
                          "  maxwell  m1     (k = 100 N/mm in [1, 10000], tau = 10 ms in [0.01, 10000])\n"
                          "  friction f1     (k = 300 N/mm in [1, 10000], uy = 30 um in [0.1, 10000])\n"
                          "  friction f2     (k = 300 N/mm in [1, 10000], uy = 300 um in [0.1, 10000])\n"
                          "}\n"
                       << fmt::format("fit {{\n  data \"{}/rig_preloaded_history.csv\"  # no force_offset\n}}\n", RHEO_DATA_DIR);
  const auto r = run_rheo(fmt::format("refine {} --rounds 3 -o {}", model.string(), final_model.string()));
  CAPTURE(r.out);
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("round 1: RMS force residual = ") != std::string::npos);
  CHECK(r.out.find("effect offset, added 'force_offset'") != std::string::npos);
  CHECK(r.out.find("round 2: ") != std::string::npos);
  CHECK(r.out.find("effect none") != std::string::npos);
  const std::string text = rheo::test::read_file(final_model.string());
  CHECK(text.find("rig_preloaded_history.csv\", force_offset = free  # no force_offset") != std::string::npos);
  // The final file fits the offset again: 150 N to the data's digits.
  const auto fitted = run_rheo(fmt::format("fit {} --json", final_model.string()));
  REQUIRE(fitted.code == 0);
  const auto j = nlohmann::json::parse(fitted.out);
  CHECK(std::abs(j["data"][0]["force_offset"]["value"].get<double>() - 150.0) < 0.01);
}

}  // namespace cli_diagnose_test
