// `--report FILE.html` and `--plot FILE.svg|FILE.png`, shared by `rheo report`, `rheo simulate`
// and `rheo fit`: registers the options and writes the files (atomically, runtime/io/output.hpp).
// The plot is report_figures.hpp's primary figure; a .png is converted from the SVG by
// rsvg-convert (Debian librsvg2-bin) when it is installed, and is a usage error naming the
// package otherwise.
#pragma once

#include "runtime/report/report_content.hpp"

#include <CLI/CLI.hpp>

#include <string>

namespace rheo::cli {

struct ReportTargets {
  std::string html;  // --report (or -o of `rheo report`)
  std::string plot;  // --plot
  bool any() const { return !html.empty() || !plot.empty(); }
};

// Adds --plot, and --report unless `html_option` is false (`rheo report` names it -o).
void add_report_options(CLI::App& app, ReportTargets& targets, bool html_option);

// Throws DataError when a file's directory does not exist or the name is a directory, and
// UsageError when the files cannot be written as asked (a .png plot without rsvg-convert): for
// commands that run long before they write.
void check_report_targets(const ReportTargets& targets);

// Writes the requested files and says so on standard error.
void write_report_files(const runtime::report::ReportContent& content, const ReportTargets& targets);

}  // namespace rheo::cli
