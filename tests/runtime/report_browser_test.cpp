// A generated report rendered in a real browser: headless Chromium (Debian's `chromium`,
// installed by .ci/install-deps) loads it from disk with the network unreachable, and the DOM
// it dumps must hold every figure with the expected number of series and reference nothing
// outside the page; the browser's log must show no console message (uncaught errors included). A screenshot is kept as the test artifact
// (BUILD_DIR/test-artifacts/specimen_d_report.png and diagnose_report.png, a `rheo diagnose`
// report; the paths are printed). Without chromium the test fails under CI (CI=true) and
// elsewhere says it is skipped.
#include "lang/frontend.hpp"
#include "runtime/io/harmonic_data.hpp"
#include "cli_support.hpp"
#include "report_support.hpp"
#include "support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

namespace report_browser_test {

namespace fs = std::filesystem;
using rheo::test::count;

namespace {

constexpr const char* kChromium = "/usr/bin/chromium";

fs::path artifacts() {
  const fs::path dir = fs::path(RHEO_BINARY).parent_path() / "test-artifacts";
  fs::create_directories(dir);
  return dir;
}

// Runs chromium on `url` with `arguments`; standard output to `out`, the browser's log to `log`.
int chromium(const std::string& arguments, const fs::path& url, const fs::path& out, const fs::path& log) {
  const fs::path profile = rheo::test::scratch_directory("report") / "chromium-profile";
  // --proxy-server to a closed port: any attempt to fetch from the network fails and is logged.
  return rheo::test::run_command(fmt::format("( timeout 180 {} --headless=new --no-sandbox --disable-gpu --disable-dev-shm-usage "
                                             "--no-first-run --user-data-dir='{}' --proxy-server=127.0.0.1:9 --enable-logging=stderr --v=0 "
                                             "{} 'file://{}' > '{}' 2> '{}' )",
                                             kChromium, profile.string(), arguments, url.string(), out.string(), log.string()))
      .code;
}

// Lines of a chromium log that report a page problem: console output, which includes uncaught
// errors and resources that failed to load.
std::vector<std::string> page_problems(const std::string& log) {
  std::vector<std::string> problems;
  std::size_t start = 0;
  while (start < log.size()) {
    const std::size_t end = std::min(log.find('\n', start), log.size());
    const std::string line = log.substr(start, end - start);
    if (line.find(":CONSOLE") != std::string::npos || line.find("Failed to load resource") != std::string::npos) problems.push_back(line);
    start = end + 1;
  }
  return problems;
}

// data-figure -> number of series, and of cells, per <figure> of a dumped DOM (in order).
std::vector<std::pair<std::string, std::size_t>> figures(const std::string& dom, const std::string& what) {
  std::vector<std::pair<std::string, std::size_t>> out;
  for (std::size_t at = dom.find("<figure"); at != std::string::npos; at = dom.find("<figure", at + 1)) {
    const std::size_t end = dom.find("</figure>", at);
    const std::string figure = dom.substr(at, end - at);
    const std::size_t name = figure.find("data-figure=\"") + 13;
    out.emplace_back(figure.substr(name, figure.find('"', name) - name), count(figure, what));
  }
  return out;
}

std::size_t leaves(const rheo::lang::Element& e) {
  if (e.kind != rheo::lang::ElementKind::parallel && e.kind != rheo::lang::ElementKind::series) return 1;
  std::size_t n = 0;
  for (const auto& c : e.children) n += leaves(c);
  return n;
}

std::size_t distinct(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return static_cast<std::size_t>(std::unique(v.begin(), v.end()) - v.begin());
}

}  // namespace

TEST_CASE("report in a browser: headless chromium renders every figure with its series, without errors") {
  const fs::path dir = artifacts();
  const std::string model = fmt::format("{}/specimen_d.rheo", RHEO_EXAMPLES_DIR);
  const std::string harmonic = fmt::format("{}/specimen_D_harmonic.csv", RHEO_DATA_DIR);
  const fs::path html = dir / "specimen_d_report.html", svg = dir / "specimen_d_stiffness.svg";
  const auto made = rheo::test::run_rheo(fmt::format("report {} --data {} --data {}/specimen_D_static.csv -o {} --plot {}", model, harmonic,
                                                     RHEO_DATA_DIR, html.string(), svg.string()));
  CAPTURE(made.err);
  REQUIRE(made.code == 0);
  if (!rheo::test::tool_installed(kChromium, "chromium")) return;

  // The detector itself: a page that logs an error must be caught.
  const fs::path bad = rheo::test::scratch_directory("report") / "bad.html";
  std::ofstream(bad) << "<!DOCTYPE html><html><body><script>console.error('broken')</script></body></html>";
  chromium("--dump-dom", bad, rheo::test::scratch_directory("report") / "bad.dom", rheo::test::scratch_directory("report") / "bad.log");
  REQUIRE_MESSAGE(!page_problems(rheo::test::read_file((rheo::test::scratch_directory("report") / "bad.log").string())).empty(),
                  "the chromium log no longer shows console errors or failed loads; the check below would prove nothing");

  const fs::path dom_file = dir / "specimen_d_report.dom.html", log_file = dir / "specimen_d_report.chromium.log";
  REQUIRE(chromium("--dump-dom", html, dom_file, log_file) == 0);
  const std::string dom = rheo::test::read_file(dom_file.string());
  const std::vector<std::string> problems = page_problems(rheo::test::read_file(log_file.string()));
  CHECK_MESSAGE(problems.empty(), fmt::format("chromium reported: {}", problems.empty() ? "" : problems.front()));
  CHECK(dom.find("<script") == std::string::npos);
  for (const char* reference : {"src=", "href=", "http", "@import"}) CHECK(dom.find(reference) == std::string::npos);

  const rheo::runtime::HarmonicData data = rheo::runtime::read_harmonic_data(harmonic);
  const std::size_t curves_over_frequency = std::min<std::size_t>(distinct(data.amplitude), 8);
  const std::size_t curves_over_amplitude = std::min<std::size_t>(distinct(data.frequency), 8);
  const std::map<std::string, std::size_t> expected_series{{"stiffness-frequency", 2 * curves_over_frequency},
                                                           {"phase-frequency", 2 * curves_over_frequency},
                                                           {"stiffness-amplitude", 2 * curves_over_amplitude},
                                                           {"phase-amplitude", 2 * curves_over_amplitude},
                                                           {"storage-frequency", 2 * curves_over_frequency},
                                                           {"loss-frequency", 2 * curves_over_frequency},
                                                           {"hysteresis", 2},
                                                           {"network", 0},
                                                           {"residual-stiffness", 0},
                                                           {"residual-phase", 0}};
  const auto series = figures(dom, "class=\"series\"");
  REQUIRE(series.size() == expected_series.size());
  std::set<std::string> seen;
  for (const auto& figure : series) {
    const auto& name = figure.first;  // not a structured binding: Clang 14 cannot capture one
    const auto& n = figure.second;
    CAPTURE(name);
    REQUIRE(expected_series.count(name) == 1);
    CHECK(n == expected_series.at(name));
    seen.insert(name);
  }
  CHECK(seen.size() == expected_series.size());
  for (const auto& [name, cells] : figures(dom, "class=\"cell\""))
    if (name.starts_with("residual")) CHECK(cells == data.size());
  const rheo::lang::Program program = rheo::lang::load_program(model);
  for (const auto& [name, elements] : figures(dom, "class=\"element\""))
    if (name == "network") CHECK(elements == leaves(program.find_model("specimen_d")->root));

  // The standalone figure is parsed as XML: a malformed file shows Chromium's parser error page.
  const fs::path svg_dom = dir / "specimen_d_stiffness.dom.xml";
  REQUIRE(chromium("--dump-dom", svg, svg_dom, dir / "specimen_d_stiffness.chromium.log") == 0);
  const std::string figure = rheo::test::read_file(svg_dom.string());
  CHECK(figure.find("parsererror") == std::string::npos);
  CHECK(count(figure, "class=\"series\"") == 2 * curves_over_frequency);

  const fs::path screenshot = dir / "specimen_d_report.png";
  fs::remove(screenshot);
  CHECK(chromium(fmt::format("--screenshot='{}' --window-size=1280,4200 --hide-scrollbars", screenshot.string()), html, dir / "screenshot.out",
                 dir / "screenshot.log") == 0);
  REQUIRE(fs::exists(screenshot));
  CHECK(fs::file_size(screenshot) > 50000);
  MESSAGE(fmt::format("screenshot of the rendered report: {}", screenshot.string()));
}

TEST_CASE("report in a browser: a diagnosis report draws the model before dashed beside the refined one, without errors") {
  const fs::path dir = artifacts();
  const fs::path model = dir / "diagnose_linear.rheo", html = dir / "diagnose_report.html";
  std::ofstream(model) << "model linear {\n  spring k0 (k = 300 N/mm in [10, 10000])\n"
                          "  friction f1 (k = 200 N/mm in [1, 10000], uy = 100 um in [0.1, 10000])\n}\n";
  const auto made = rheo::test::run_rheo(
      fmt::format("diagnose {} --data {}/specimen_D_static.csv --report {}", model.string(), RHEO_DATA_DIR, html.string()));
  CAPTURE(made.err);
  REQUIRE(made.code == 0);
  if (!rheo::test::tool_installed(kChromium, "chromium")) return;
  const fs::path dom_file = dir / "diagnose_report.dom.html", log_file = dir / "diagnose_report.chromium.log";
  REQUIRE(chromium("--dump-dom", html, dom_file, log_file) == 0);
  const std::string dom = rheo::test::read_file(dom_file.string());
  const std::vector<std::string> problems = page_problems(rheo::test::read_file(log_file.string()));
  CHECK_MESSAGE(problems.empty(), fmt::format("chromium reported: {}", problems.empty() ? "" : problems.front()));
  for (const char* reference : {"<script", "src=", "href=", "http", "@import"}) CHECK(dom.find(reference) == std::string::npos);
  // Figures in page order: the refined network, the loop (measured, model before, refined), the network before.
  const auto series = figures(dom, "class=\"series\"");
  REQUIRE(series.size() == 3);
  CHECK(series[0] == std::pair<std::string, std::size_t>{"network", 0});
  CHECK(series[1] == std::pair<std::string, std::size_t>{"hysteresis", 3});
  CHECK(series[2] == std::pair<std::string, std::size_t>{"network-before", 0});
  CHECK(count(dom, "data-style=\"dashed\"") == 1);
  CHECK(dom.find("<h2>Diagnosis</h2>") != std::string::npos);
  const fs::path screenshot = dir / "diagnose_report.png";
  fs::remove(screenshot);
  CHECK(chromium(fmt::format("--screenshot='{}' --window-size=1280,3600 --hide-scrollbars", screenshot.string()), html,
                 dir / "diagnose_screenshot.out", dir / "diagnose_screenshot.log") == 0);
  CHECK(fs::exists(screenshot));
  MESSAGE(fmt::format("screenshot of the rendered diagnosis report: {}", screenshot.string()));
}

}  // namespace report_browser_test
