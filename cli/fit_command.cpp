// `rheo fit FILE [--data CSV]... [-o FITTED.rheo] [--json] ...`: runs the file's fit blocks
// (or a default fit of its model when it has none) and reports; see docs/cli.md.
#include "lang/fitted_source.hpp"
#include "lang/frontend.hpp"
#include "cli/data_option.hpp"
#include "cli/commands.hpp"
#include "cli/fit_job.hpp"
#include "cli/model_output.hpp"
#include "cli/program_lookup.hpp"
#include "cli/report_files.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/fit/fit_report.hpp"
#include "runtime/io/output.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>

namespace rheo::cli {
namespace {

// SOURCE: the text the fitted model was compiled from (not the file as it is after the fit).
std::string fitted_file_text(const FitJob& job, const runtime::FitResult& result, const std::string& source_file, const std::string& source) {
  std::vector<std::string> header{
      fmt::format("Fitted by `rheo fit` (method {}, objective {}) to:", job.description.method, job.description.objective)};
  std::vector<lang::FittedSetting> offsets;
  lang::Parameter newton;  // how a force is written: in N
  newton.dimension = lang::dim::force;
  newton.unit = "N";
  for (std::size_t k = 0; k < result.datasets.size(); ++k) {
    const runtime::DataSetFit& set = result.datasets[k];
    header.push_back(fmt::format("  {} (weight {:g}): err = {:.6g}", set.path, set.weight, set.err));
    if (set.harmonic || !set.force_offset.given || !set.force_offset.free) continue;
    // A fitted offset is written into its data line; one given by --data has no line here.
    const std::string value = lang::format_parameter_value(newton, set.force_offset.value);
    const lang::ForceOffsetSetting* line = k < job.lines.size() ? &job.lines[k].force_offset : nullptr;
    if (line && line->free && line->where.file == source_file && line->value_begin >= 0) {
      offsets.push_back({line->value_begin, line->value_end, value});
      header.back() += fmt::format(", force_offset fitted to {} (written on its data line)", value);
    } else {
      header.back() += fmt::format(", force_offset fitted to {}: give `force_offset = {}` on its data line to reuse it", value, value);
    }
  }
  if (result.phi > 0.0) header.push_back(fmt::format("phi (5.1) = {:.6g}, err (6.1) = {:.6g}", result.phi, result.err));
  if (result.interrupted) header.push_back("Interrupted: the best values found before the interruption.");
  header.push_back(fmt::format("Start values: {}", source_file));
  return lang::write_fitted_source(source, source_file, result.network.model(), result.network.parameters(), result.free, header, offsets);
}

}  // namespace

Command add_fit_command(CLI::App& app) {
  auto o = std::make_shared<FitOptions>();
  auto report = std::make_shared<ReportTargets>();
  app.add_option("file", o->file, "The .rheo file: a model with bounds on the parameters to fit, and optionally fit blocks")->required();
  app.add_option("--data", o->data,
                 std::string("Measured data (harmonic table or time history): ") + data_option_settings_help +
                     "; replaces the fit block's data lines. Repeatable");
  app.add_option("-o,--output", o->output,
                 "Write the fitted model (.rheo, comments kept) here; needs exactly one fit to run (with --orders: the structure of lowest AIC)");
  app.add_flag("--json", o->json, "Print the JSON summary instead of the text report");
  app.add_option("--model", o->model, "Fit only this model's fit blocks (or this model, when the file has none)");
  app.add_option("--block", o->block, "Run only the N-th fit block of the file (1-based)")->check(CLI::Range(1, std::numeric_limits<int>::max()));
  // Defaults: the fit block's setting, else these (runtime::SearchSettings).
  const runtime::SearchSettings defaults;
  app.add_option("--method", o->method, "exact | approximate | corrected (thesis eqs. 5.5-5.21, Table 5.1); default exact");
  app.add_option("--optimizer", o->optimizer, "default | bobyqa | sbplx | neldermead | direct_l | crs2 | isres | mlsl; default: default");
  app.add_option(
         "--max-evaluations", o->max_evaluations,
         fmt::format(
             "Evaluation budget of the search over all its stages; default {}. The exact method's cheaper surrogate stage has a budget of its own, so the count reported can reach twice this",
             defaults.max_evaluations))
      ->check(CLI::Range(1, std::numeric_limits<int>::max()));
  app.add_option("--starts", o->starts, fmt::format("Local searches of the default strategy; default {}", defaults.starts))
      ->check(CLI::Range(1, std::numeric_limits<int>::max()));
  app.add_option("--seed", o->seed,
                 fmt::format("Seed of the sampling and stochastic optimizers; the same seed gives the same result; default {}", defaults.seed))
      ->check(CLI::Range(0LL, std::numeric_limits<long long>::max()));
  app.add_option("--time-limit", o->time_limit,
                 "Wall-clock bound of each fit, e.g. 60s or 5min: the search stops in time for the standard errors and reports the best "
                 "values found (status TIME_LIMIT_REACHED); default: the fit block's time_limit, else none");
  app.add_flag("--progress", o->progress,
               "Write a progress line to standard error every second, also on a terminal; without it a live line on a terminal, else a line "
               "every 5 s");
  app.add_option("--threads", o->threads, "Harmonic points evaluated at once (0: every hardware thread); results do not depend on it; default 1")
      ->check(CLI::Range(0, 1024));
  app.add_option("--yeoh-start", o->yeoh_start,
                 "Static or quasi-static loop (CSV) whose mean curve gives the yeoh spring's start values by least squares (eqs. 5.28-5.32)");
  app.add_option(
      "--orders", o->orders,
      "Model-order study (thesis Fig. 6.2), e.g. maxwell=1..4,friction=1..6: fits each structure, tables err (6.1); -o writes the chosen one");
  add_report_options(app, *report, true);
  app.footer(
      "Settings given here override the fit block's. Data lines and `output` in a fit block are relative to the\n"
      ".rheo file; --data and -o to the working directory. The report goes to standard output, messages to standard\n"
      "error, with progress: a live line on a terminal, else a line every 5 s (--progress: a line every second).\n"
      "Ctrl-C stops the search and writes the best result so far (exit code 130).");
  return [o, report] {
    check_report_targets(*report);
    // Read once: the fitted file is written from the text compiled, however the file changes meanwhile.
    const std::string source = lang::read_source(o->file);
    const lang::Program program = lang::compile_source(o->file, source);
    std::vector<FitJob> jobs = fit_jobs(program, *o);
    if (report->any() && !o->orders.empty())
      throw runtime::UsageError("--report and --plot show one fit, --orders many: run the study, then fit the structure chosen with --report");
    if (!o->orders.empty()) return run_order_study(jobs, *o);
    if (!o->output.empty() && jobs.size() != 1)
      throw runtime::UsageError(fmt::format("-o names one output but {} fits would run; select one with --model or --block N", jobs.size()));
    if (report->any() && jobs.size() != 1)
      throw runtime::UsageError(fmt::format("--report and --plot show one fit but {} would run; select one with --model or --block N", jobs.size()));
    std::vector<std::string> json_reports;
    bool interrupted = false;
    for (std::size_t k = 0; k < jobs.size(); ++k) {
      FitJob& job = jobs[k];
      const runtime::FitResult result = run_fit_job(job);
      interrupted = interrupted || result.interrupted;
      if (report->any()) write_report_files(runtime::report::report_from_fit(result, job.data, job.description), *report);
      if (!job.output.empty()) {
        write_model_file(job.output, fitted_file_text(job, result, o->file, source), o->file);
        std::cerr << fmt::format("rheo: fitted model {} written to {}\n", result.network.model().name, job.output);
      }
      if (o->json) {
        json_reports.push_back(runtime::fit_report_json(job.description, result));
      } else {
        // Flushed: the next fit's messages on standard error follow it in a log as on a terminal.
        std::cout << runtime::fit_report_text(job.description, result) << (k + 1 < jobs.size() ? "\n" : "") << std::flush;
      }
      if (result.interrupted) break;
    }
    if (o->json) std::cout << (json_reports.size() == 1 ? json_reports.front() : fmt::format("[\n{}]\n", fmt::join(json_reports, ",\n")));
    return interrupted ? exit_code_interrupted : runtime::exit_code::ok;
  };
}

}  // namespace rheo::cli
