#include "cli/report_files.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/io/output.hpp"
#include "runtime/report/html_report.hpp"
#include "runtime/report/report_figures.hpp"

#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <vector>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

extern char** environ;

namespace rheo::cli {
namespace {

namespace fs = std::filesystem;

std::string find_on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const fs::path candidate = fs::path(dir.empty() ? "." : dir) / program;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return {};
}

bool wants_png(const ReportTargets& targets) { return fs::path(targets.plot).extension() == ".png"; }

std::string png_converter(const std::string& target) {
  const std::string converter = find_on_path("rsvg-convert");
  if (converter.empty())
    throw runtime::UsageError(
        fmt::format("--plot {}: writing PNG needs rsvg-convert (Debian package librsvg2-bin); install it, "
                    "or write an .svg file instead",
                    target));
  return converter;
}

// The PNG bytes of an SVG document, by rsvg-convert.
std::string png_of(const std::string& svg, const std::string& target) {
  const std::string converter = png_converter(target);
  const fs::path dir = fs::temp_directory_path() / fmt::format("rheo-plot-{}", ::getpid());
  fs::create_directories(dir);
  const fs::path svg_file = dir / "plot.svg", png_file = dir / "plot.png";
  std::ofstream(svg_file, std::ios::binary) << svg;
  std::string args[] = {converter, "--background-color=white", "-o", png_file.string(), svg_file.string()};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  int status = -1;
  if (::posix_spawn(&pid, converter.c_str(), nullptr, nullptr, argv.data(), environ) == 0) ::waitpid(pid, &status, 0);
  std::ifstream in(png_file, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  std::error_code ignored;
  fs::remove_all(dir, ignored);
  if (status != 0 || bytes.str().empty())
    throw runtime::DataError(
        fmt::format("--plot {}: rsvg-convert could not convert the plot (exit status {}); write an .svg file instead", target, status));
  return bytes.str();
}

}  // namespace

void add_report_options(CLI::App& app, ReportTargets& targets, bool html_option) {
  if (html_option) app.add_option("--report", targets.html, "Also write a self-contained HTML report (plots, network diagram, parameters) here");
  app.add_option("--plot", targets.plot,
                 "Also write one figure here: stiffness over frequency (a curve per amplitude), or the hysteresis loop when there "
                 "is no harmonic grid; .svg, or .png when rsvg-convert is installed");
}

void check_report_targets(const ReportTargets& targets) {
  runtime::check_output_destination(targets.html);
  runtime::check_output_destination(targets.plot);
  if (wants_png(targets)) png_converter(targets.plot);
}

void write_report_files(const runtime::report::ReportContent& content, const ReportTargets& targets) {
  if (!targets.plot.empty()) {
    const std::string svg = runtime::report::primary_figure_svg(content);
    runtime::write_output(targets.plot, wants_png(targets) ? png_of(svg, targets.plot) : svg);
    if (targets.plot != "-") std::cerr << fmt::format("rheo: plot written to {}\n", targets.plot);
  }
  if (!targets.html.empty()) {
    runtime::write_output(targets.html, runtime::report::html_report(content));
    if (targets.html != "-") std::cerr << fmt::format("rheo: report written to {}\n", targets.html);
  }
}

}  // namespace rheo::cli
