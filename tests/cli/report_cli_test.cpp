// `rheo report`, `--report` and `--plot` through the real binary, on the examples (so that they
// never rot), with the exit codes of docs/cli.md.
#include "cli_support.hpp"
#include "report_support.hpp"
#include "support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

using rheo::test::count;
using rheo::test::run_rheo;

namespace {
std::string example(const std::string& name) { return fmt::format("{}/{}", RHEO_EXAMPLES_DIR, name); }
std::string data(const std::string& name) { return fmt::format("{}/{}", RHEO_DATA_DIR, name); }
}  // namespace

TEST_CASE("rheo report: specimen D against its harmonic and static data") {
  const auto dir = rheo::test::scratch_directory("report");
  const auto html = dir / "specimen_d.html", svg = dir / "specimen_d.svg";
  const auto r = run_rheo(fmt::format("report {} --data {} --data {} -o {} --plot {}", example("specimen_d.rheo"), data("specimen_D_harmonic.csv"),
                                      data("specimen_D_static.csv"), html.string(), svg.string()));
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.find("report written to") != std::string::npos);
  const std::string page = rheo::test::read_file(html.string());
  CHECK(count(page, "<figure") == 8);
  CHECK(count(page, "data-figure=\"hysteresis\"") == 1);
  CHECK(count(page, "class=\"element\"") == 8);  // yeoh, maxwell, 6 friction
  CHECK(page.find("err (6.1) = ") != std::string::npos);
  CHECK(page.find("http") == std::string::npos);
  const std::string figure = rheo::test::read_file(svg.string());
  CHECK(figure.starts_with("<?xml"));
  CHECK(rheo::test::xml_problem(figure) == "");
  CHECK(count(figure, "class=\"series\"") == 14);  // 7 amplitudes, measured and model
}

TEST_CASE("rheo report: without data, the simulate protocols; errors exit 2 and 4") {
  const auto dir = rheo::test::scratch_directory("report");
  const auto html = dir / "bushing_d.html";
  const auto r = run_rheo(fmt::format("report {} -o {}", example("bushing_d.rheo"), html.string()));
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  const std::string page = rheo::test::read_file(html.string());
  CHECK(count(page, "<figure") == 5);  // network and 4 curve plots, no residual maps without data
  CHECK(page.find("model only (no measurements)") != std::string::npos);
  CHECK(count(page, "class=\"series\"") == 4 * 2 + 2 * 8);  // 4 amplitudes; 8 of 26 frequencies

  const auto nothing = run_rheo(fmt::format("report {}", example("bushing_d.rheo")));
  CHECK(nothing.code == 2);
  CHECK(nothing.err.find("-o REPORT.html") != std::string::npos);
  const auto missing = run_rheo(fmt::format("report {} --data {} -o {}", example("bushing_d.rheo"), (dir / "none.csv").string(), html.string()));
  CHECK(missing.code == 4);
  CHECK(missing.err.find("none.csv") != std::string::npos);
}

TEST_CASE("rheo simulate --report and rheo fit --report") {
  const auto dir = rheo::test::scratch_directory("report");
  const auto sim = dir / "sim.html";
  const auto s = run_rheo(
      fmt::format("simulate {} --protocol harmonic -o {} --report {}", example("bushing_d.rheo"), (dir / "grid.csv").string(), sim.string()));
  CAPTURE(s.err);
  REQUIRE(s.code == 0);
  CHECK(count(rheo::test::read_file(sim.string()), "data-figure=\"stiffness-frequency\"") == 1);

  const auto fit = dir / "fit.html";
  const auto f = run_rheo(fmt::format("fit {} --max-evaluations 30 -o {} --report {} --plot {}", example("specimen_d_fit.rheo"),
                                      (dir / "fitted.rheo").string(), fit.string(), (dir / "fit.svg").string()));
  CAPTURE(f.err);
  REQUIRE(f.code == 0);
  const std::string page = rheo::test::read_file(fit.string());
  CHECK(page.find("<th>std. error</th>") != std::string::npos);
  CHECK(page.find("<th>start</th>") != std::string::npos);
  CHECK(count(page, "data-figure=\"residual-stiffness\"") == 1);
  CHECK(count(page, "<tr class=\"free\">") == 17);  // every bounded parameter of specimen_d_fit
  CHECK(rheo::test::read_file((dir / "fit.svg").string()).starts_with("<?xml"));
}

TEST_CASE("rheo report --plot FILE.png: converted by rsvg-convert, a usage error naming it where it is not on PATH") {
  const auto dir = rheo::test::scratch_directory("report");
  const auto png = dir / "plot.png";
  const std::string arguments = fmt::format("report {} --data {} --plot {}", example("specimen_c.rheo"), data("specimen_C_harmonic.csv"),
                                            png.string());
  // Without the converter on PATH (rheo needs nothing else from it): refused, naming the package.
  const auto without = run_rheo(arguments, "PATH=/nonexistent");
  CAPTURE(without.err);
  CHECK(without.code == 2);
  CHECK(without.err.find("librsvg2-bin") != std::string::npos);
  CHECK(!std::filesystem::exists(png));
  if (!rheo::test::tool_installed("rsvg-convert", "librsvg2-bin")) return;
  const auto r = run_rheo(arguments);
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  CHECK(rheo::test::read_file(png.string()).starts_with("\x89PNG"));
}
