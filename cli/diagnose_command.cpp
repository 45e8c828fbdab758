// `rheo diagnose FILE --data CSV... [-o REFINED.rheo] [--json] [--report R.html] [--plot P.svg]`
// and `rheo refine FILE --data CSV... [-o FINAL.rheo] [--rounds N] [--report ...] [--plot ...]`: name the effect a model misses,
// add the element that supplies it and refit (runtime/diagnosis/diagnose.hpp); see docs/cli.md.
#include "cli/model_output.hpp"
#include "lang/frontend.hpp"
#include "lang/limits.hpp"
#include "cli/data_option.hpp"
#include "cli/commands.hpp"
#include "cli/fit_job.hpp"
#include "cli/program_lookup.hpp"
#include "cli/progress.hpp"
#include "cli/report_files.hpp"
#include "runtime/diagnosis/diagnosis_html.hpp"
#include "runtime/diagnosis/diagnosis_report.hpp"
#include "runtime/fit/fit_report.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/io/output.hpp"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>

namespace rheo::cli {
namespace {

namespace dx = runtime::diagnosis;

struct DiagnoseOptions {
  FitOptions fit;
  ReportTargets report;
  int candidates = 3;
  int steps_per_cycle = 0;  // 0: the fit block's, else 128
  int rounds = 5;           // refine
};

void add_common_options(CLI::App& app, DiagnoseOptions& o) {
  app.add_option("file", o.fit.file, "The .rheo file: the model, with bounds on the parameters to fit")->required();
  app.add_option("--data", o.fit.data,
                 std::string("Measured data (harmonic table or time history): ") + data_option_settings_help +
                     "; replaces the fit block's data lines. Repeatable");
  app.add_option("--model", o.fit.model, "The model to diagnose (when the file has several)");
  app.add_option("--block", o.fit.block, "Take model, data and settings from the N-th fit block of the file (1-based)")
      ->check(CLI::Range(1, std::numeric_limits<int>::max()));
  app.add_option("--candidates", o.candidates, "Leading effects confirmed by a refit; default 3")->check(CLI::Range(1, 5));
  app.add_option("--steps-per-cycle", o.steps_per_cycle,
                 "Time steps per cycle where harmonic points are time-stepped, a multiple of 4; default: the fit block's, else 128")
      ->check(CLI::Range(16, lang::max_steps_per_cycle))
      ->check([](const std::string& text) {
        int steps = 0;
        const bool whole = CLI::detail::lexical_cast(text, steps);
        return whole && steps % 4 == 0 ? std::string() : "must be a multiple of 4 (the turning points are sampled), e.g. 128";
      });
  app.add_option("--seed", o.fit.seed, "Seed of the searches' sampling; the same seed gives the same result; default 1")
      ->check(CLI::Range(0LL, std::numeric_limits<long long>::max()));
  app.add_option("--threads", o.fit.threads, "Harmonic points evaluated at once (0: every hardware thread); results do not depend on it; default 1")
      ->check(CLI::Range(0, 1024));
  app.add_option("--time-limit", o.fit.time_limit,
                 "Wall-clock bound of the whole run, e.g. 60s or 5min: fits stop in time and what has not begun is skipped; the results so "
                 "far are reported (time_limited); default: none (each fit is bounded by the fit block's time_limit, if any)");
  app.add_flag("--progress", o.fit.progress,
               "Write a progress line to standard error every second, also on a terminal; without it a live line on a terminal, else a line "
               "every 5 s");
  add_report_options(app, o.report, true);
}

struct Prepared {
  lang::Program program;
  FitJob job;
  dx::ModelSource source;
  dx::DiagnoseSettings settings;
  std::shared_ptr<Progress> progress;
  std::optional<double> time_limit;  // --time-limit [s]
};

std::unique_ptr<Prepared> prepare(const DiagnoseOptions& o) {
  check_report_targets(o.report);
  auto p = std::make_unique<Prepared>();
  const std::string text = lang::read_source(o.fit.file);  // read once: diagnose edits the text compiled
  p->program = lang::compile_source(o.fit.file, text);
  FitOptions per_fit = o.fit;
  per_fit.time_limit.clear();  // --time-limit bounds the whole run, not each fit
  std::vector<FitJob> jobs = fit_jobs(p->program, per_fit);
  if (jobs.size() != 1)
    throw runtime::UsageError(fmt::format("{} has {} fit blocks; choose the one to diagnose with --block N or --model NAME", o.fit.file, jobs.size()));
  p->job = std::move(jobs.front());
  p->source = {o.fit.file, text, p->job.model->name, p->job.lines_block};
  p->settings.fit = p->job.settings;
  if (o.steps_per_cycle > 0) p->settings.fit.score.harmonic.steps_per_cycle = o.steps_per_cycle;
  else if (!p->job.steps_per_cycle_given) p->settings.fit.score.harmonic.steps_per_cycle = 128;
  for (int i : p->job.free) p->settings.free.push_back(p->job.model->parameters[static_cast<std::size_t>(i)].path);
  p->settings.confirm = o.candidates;
  p->settings.standard_errors = o.report.any();  // the report's parameter table shows them
  if (!o.fit.time_limit.empty()) p->time_limit = duration_option(o.fit.time_limit, "--time-limit");
  p->progress = Progress::start(o.fit.progress, p->time_limit);
  p->settings.stage = Progress::stage_callback(p->progress);
  p->settings.fit.progress = Progress::evaluation_callback(p->progress);
  if (p->time_limit)
    p->settings.deadline = std::chrono::steady_clock::now() +
                           std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(*p->time_limit));
  return p;
}

void write_report(const DiagnoseOptions& o, const Prepared& p, const std::vector<dx::Diagnosis>& rounds, const char* command) {
  if (o.report.any()) write_report_files(dx::diagnosis_report_content(rounds, p.job.data, p.job.description, command), o.report);
}

std::vector<std::string> free_paths(const runtime::FitResult& fit) {
  std::vector<std::string> paths;
  for (int i : fit.free) paths.push_back(fit.network.model().parameters[static_cast<std::size_t>(i)].path);
  return paths;
}

// "  round 2: err (6.1) = 0.0131 -> 0.00204 (6.42 times lower)  effect rate-dependence, added 'relaxation'; noise
// leaves 0.00198, the gap is 1.03 times that".
std::string round_line(int round, const dx::Diagnosis& d) {
  std::string line = fmt::format("  round {}: {} = {:.4g} -> {:.4g}", round, d.gap_name, d.gap_before, d.gap_after);
  if (d.verdict == dx::Verdict::named) line += fmt::format(" ({:.2f} times lower)", d.gap_before / d.gap_after);
  line += fmt::format("  effect {}", dx::verdict_name(d));
  if (!d.added_element.empty()) line += fmt::format(", added '{}'", d.added_element);
  if (d.noise.estimated) line += fmt::format("; noise leaves {:.4g}, the gap before is {:.2f} times that", d.noise.floor, d.noise_ratio);
  return line + "\n";
}

std::string default_refined_path(const std::string& file) {
  std::filesystem::path path(file);
  return (path.parent_path() / (path.stem().string() + "_refined.rheo")).string();
}

}  // namespace

Command add_diagnose_command(CLI::App& app) {
  auto o = std::make_shared<DiagnoseOptions>();
  add_common_options(app, *o);
  app.add_option("-o,--output", o->fit.output, "Write the refined model (.rheo: the file with fitted values and the added element) here");
  app.add_flag("--json", o->fit.json, "Print the JSON summary instead of the text report");
  app.footer(
      "Fits the model, screens every effect (amplitude-dependence, rate-dependence, nonlinear-elasticity,\n"
      "coupled-amplitude-frequency, inertia) by the share of the residual the matching element explains, refits the\n"
      "leading ones and names the effect whose element earns its parameters (BIC); else `none` when the residual is\n"
      "at the measurement noise estimated from it, `unexplained` when it is more. See docs/cli.md.");
  return [o] {
    const auto p = prepare(*o);
    InterruptScope interrupt_scope;
    p->settings.fit.interrupt = interrupt_scope.flag();
    const dx::Diagnosis d = dx::diagnose(p->source, p->job.data, p->settings);
    p->progress->finish();
    if (!o->fit.output.empty()) {
      write_model_file(o->fit.output, d.refined_text, o->fit.file);
      std::cerr << fmt::format("rheo: refined model {} written to {}\n", p->source.model, o->fit.output);
    }
    write_report(*o, *p, {d}, "rheo diagnose");
    std::cout << (o->fit.json ? dx::diagnosis_report_json(o->fit.file, d, o->fit.output) : dx::diagnosis_report_text(o->fit.file, d));
    return d.interrupted ? exit_code_interrupted : runtime::exit_code::ok;
  };
}

Command add_refine_command(CLI::App& app) {
  auto o = std::make_shared<DiagnoseOptions>();
  add_common_options(app, *o);
  app.add_option("-o,--output", o->fit.output, "Write the final model here; default FILE_refined.rheo beside FILE");
  app.add_option("--rounds", o->rounds, "Most diagnose-add-refit rounds; default 5")->check(CLI::Range(1, 20));
  app.footer(
      "Repeats `rheo diagnose` on its own refined model until the verdict is `none` (the gap at the noise) or\n"
      "`unexplained`, or the rounds or --time-limit are spent, printing each round's gain, and writes the final\n"
      "model. See docs/cli.md.");
  return [o] {
    const auto p = prepare(*o);
    const std::string output = o->fit.output.empty() ? default_refined_path(o->fit.file) : o->fit.output;
    dx::ModelSource source = p->source;
    dx::DiagnoseSettings settings = p->settings;
    InterruptScope interrupt_scope;
    settings.fit.interrupt = interrupt_scope.flag();
    bool interrupted = false;
    std::vector<dx::Diagnosis> rounds;
    for (int round = 1; round <= o->rounds; ++round) {
      const dx::Diagnosis& d = rounds.emplace_back(dx::diagnose(source, p->job.data, settings));
      p->progress->finish();
      if (round == 1) std::cout << fmt::format("rheo refine: model {} from {}; gap measure {}\n", source.model, o->fit.file, d.gap_name);
      std::cout << round_line(round, d);
      if (d.after)
        for (const std::string& note : runtime::bound_notes(*d.after)) std::cout << "    " << note << "\n";
      std::cout << std::flush;  // before the next round's stages on standard error, in a log as on a terminal
      source.text = d.refined_text;
      if (d.after) settings.free = free_paths(*d.after);  // the added element's parameters join; a replaced one's leave
      for (std::size_t k : d.freed_offsets)               // the offset the refined file fits, fitted in the later rounds too
        p->job.data[k].force_offset = runtime::ForceOffset{.given = true, .free = true, .value = 0.0};
      interrupted = d.interrupted;
      if (d.verdict != dx::Verdict::named || interrupted) break;
      if (d.time_limited) {
        std::cout << "  stopped at the time limit (--time-limit); the last model may still miss an effect\n";
        break;
      }
      if (round == o->rounds) std::cout << fmt::format("  stopped after {} rounds (--rounds); the last model may still miss an effect\n", round);
    }
    write_model_file(output, source.text, o->fit.file);
    std::cerr << fmt::format("rheo: final model {} written to {}\n", source.model, output);
    write_report(*o, *p, rounds, "rheo refine");
    return interrupted ? exit_code_interrupted : runtime::exit_code::ok;
  };
}

}  // namespace rheo::cli
