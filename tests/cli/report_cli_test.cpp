// `rheo report`, `--report` and `--plot` through the real binary, on the examples (so that they
// never rot), with the exit codes of docs/cli.md.
#include "cli_support.hpp"
#include "report_support.hpp"
#include "support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cmath>
#include <fstream>

namespace report_cli_test {

using rheo::test::count;
using rheo::test::run_rheo;

namespace {
std::string example(const std::string& name) { return fmt::format("{}/{}", RHEO_EXAMPLES_DIR, name); }
std::string data(const std::string& name) { return fmt::format("{}/{}", RHEO_DATA_DIR, name); }
void write_text(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }
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
  CHECK(count(page, "<figure") == 10);
  CHECK(count(page, "data-figure=\"hysteresis\"") == 1);
  CHECK(count(page, "class=\"element\"") == 8);  // yeoh, maxwell, 6 friction
  CHECK(page.find("err (6.1) = ") != std::string::npos);
  CHECK(page.find("http") == std::string::npos);
  const std::string figure = rheo::test::read_file(svg.string());
  CHECK(figure.starts_with("<?xml"));
  CHECK(rheo::test::xml_problem(figure) == "");
  CHECK(count(figure, "class=\"series\"") == 14);  // 7 amplitudes, measured and model
}

TEST_CASE("rheo report: without data, the simulate protocols, errors exit 2 and 4") {
  const auto dir = rheo::test::scratch_directory("report");
  const auto html = dir / "bushing_d.html";
  const auto r = run_rheo(fmt::format("report {} -o {}", example("bushing_d.rheo"), html.string()));
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  const std::string page = rheo::test::read_file(html.string());
  CHECK(count(page, "<figure") == 7);  // network and 6 curve plots, no residual maps without data
  CHECK(page.find("model only (no measurements)") != std::string::npos);
  CHECK(count(page, "class=\"series\"") == 4 * 4 + 2 * 8);  // 4 amplitudes over frequency (4 plots); 8 of 26 frequencies (2)

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

TEST_CASE("rheo report: a TRIOS amplitude sweep at one frequency is drawn over amplitude, as moduli over strain, geometry named") {
  const auto dir = rheo::test::scratch_directory("report");
  const auto html = dir / "trios.html", svg = dir / "trios.svg";
  const auto r = run_rheo(fmt::format("report {} -o {} --plot {}", example("trios_amplitude_sweep_fit.rheo"), html.string(), svg.string()));
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  const std::string page = rheo::test::read_file(html.string());
  for (const char* kind : {"stiffness-amplitude", "phase-amplitude", "storage-amplitude", "loss-amplitude"})
    CHECK(count(page, fmt::format("data-figure=\"{}\"", kind)) == 1);
  CHECK(count(page, "data-figure=\"stiffness-frequency\"") == 0);  // no stack of points at 1 Hz
  CHECK(page.find("TRIOS step &quot;Amplitude sweep") != std::string::npos);
  CHECK(page.find("area A = 490.874 mm^2, height h = 1 mm") != std::string::npos);
  CHECK(page.find("strain [%]") != std::string::npos);
  CHECK(page.find("[MPa]") != std::string::npos);
  const std::string figure = rheo::test::read_file(svg.string());
  CHECK(figure.find("Dynamic stiffness over amplitude") != std::string::npos);
  CHECK(figure.find("amplitude [mm] (log)") != std::string::npos);
}

TEST_CASE("rheo report: a Prony master curve over 18 decades, log axes with decade labels") {
  const auto dir = rheo::test::scratch_directory("report");
  const auto html = dir / "prony.html", svg = dir / "prony.svg";
  const auto r = run_rheo(fmt::format("report {} -o {} --plot {}", example("prony_fit.rheo"), html.string(), svg.string()));
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  const std::string page = rheo::test::read_file(html.string());
  for (const char* kind : {"stiffness-frequency", "phase-frequency", "storage-frequency", "loss-frequency"})
    CHECK(count(page, fmt::format("data-figure=\"{}\"", kind)) == 1);
  CHECK(count(page, "data-figure=\"stiffness-amplitude\"") == 0);
  CHECK(page.find("meta source") == std::string::npos);  // a plain table
  const std::string figure = rheo::test::read_file(svg.string());
  CHECK(figure.find("frequency [Hz] (log)") != std::string::npos);
  CHECK(figure.find(">1e-9<") != std::string::npos);
  CHECK(figure.find("e+") == std::string::npos);
}

TEST_CASE("rheo report scores fit-block data with the block's definition, as rheo fit --report does") {
  // Noise-free first-harmonic data of a spring and a friction element (whose thesis and
  // first-harmonic stiffness and phase differ), and that model fitted to it under
  // definition = first_harmonic: err is rounding there, 1e-3 or more under the thesis definition.
  const auto dir = rheo::test::scratch_directory("report_definition");
  const std::string model = "model t {\n  spring k (k = 100 N/mm in [1, 1000])\n  friction f (k = 200 N/mm in [1, 1000], uy = 50 um in [1, 1000])\n}\n";
  write_text((dir / "truth.rheo").string(),
             model +
                 "simulate {\n  harmonic frequency = [1, 10] Hz, amplitude = [0.02, 0.1, 0.5] mm, definition = first_harmonic\n"
                 "  output \"truth.csv\"\n}\n");
  REQUIRE(run_rheo("simulate " + (dir / "truth.rheo").string()).code == 0);
  const auto file = dir / "fit.rheo";
  write_text(file.string(), model + "fit t {\n  data \"truth.csv\"\n  definition = first_harmonic\n}\n");
  auto err_on_page = [](const std::string& page) {
    const auto at = page.find("err (6.1) = ");
    REQUIRE(at != std::string::npos);
    return std::stod(page.substr(at + 12, 12));
  };
  const auto r = run_rheo(fmt::format("report {} -o {}", file.string(), (dir / "block.html").string()));
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  CHECK(err_on_page(rheo::test::read_file((dir / "block.html").string())) < 1e-8);
  // --data takes the settings of the model's fit block too; a file without one, the thesis definition.
  REQUIRE(run_rheo(fmt::format("report {} --data {} -o {}", file.string(), (dir / "truth.csv").string(), (dir / "data.html").string())).code == 0);
  CHECK(err_on_page(rheo::test::read_file((dir / "data.html").string())) < 1e-8);
  write_text((dir / "plain.rheo").string(), model);
  REQUIRE(
      run_rheo(fmt::format("report {} --data {} -o {}", (dir / "plain.rheo").string(), (dir / "truth.csv").string(), (dir / "plain.html").string())).code ==
      0);
  CHECK(err_on_page(rheo::test::read_file((dir / "plain.html").string())) > 1e-4);
}

TEST_CASE("rheo report draws a history protocol from its stream, the page of the history held whole") {
  const auto dir = rheo::test::scratch_directory("report-stream");
  std::string csv = "time [s],displacement [mm]\n";
  for (int k = 0; k <= 4000; ++k) csv += fmt::format("{},{}\n", k * 1e-3, 1.5 * std::sin(k * 6.283185307179586e-3));
  write_text((dir / "loop.csv").string(), csv);
  write_text((dir / "loop.rheo").string(),
             "model s {\n  spring k1 (k = 10 N/mm)\n  friction f1 (k = 50 N/mm, uy = 0.2 mm)\n}\n"
             "simulate {\n  history file = \"loop.csv\"\n}\n");
  const auto r = run_rheo(fmt::format("report {} -o {}", (dir / "loop.rheo").string(), (dir / "streamed.html").string()));
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  // The history held whole: simulate --json (not streamed) draws the same page but for its origin.
  const auto held = run_rheo(fmt::format("simulate {} --json -o {} --report {}", (dir / "loop.rheo").string(), (dir / "loop.json").string(),
                                         (dir / "held.html").string()));
  REQUIRE(held.code == 0);
  std::string page = rheo::test::read_file((dir / "streamed.html").string());
  CHECK(count(page, "data-figure=\"hysteresis\"") == 1);
  CHECK(count(page, "rheo report") >= 1);
  for (std::size_t at; (at = page.find("rheo report")) != std::string::npos;) page.replace(at, 11, "rheo simulate");
  CHECK(page == rheo::test::read_file((dir / "held.html").string()));
}

}  // namespace report_cli_test
