// `rheo diagnose FILE --data CSV... [-o REFINED.rheo] [--json] [--report R.html] [--plot P.svg]`
// and `rheo refine FILE --data CSV... [-o FINAL.rheo] [--rounds N] [--report ...] [--plot ...]`: name the effect a model misses,
// add the element that supplies it and refit (runtime/diagnosis/diagnose.hpp); see docs/cli.md.
#include "lang/frontend.hpp"
#include "lang/limits.hpp"
#include "cli/data_option.hpp"
#include "cli/commands.hpp"
#include "cli/fit_job.hpp"
#include "cli/program_lookup.hpp"
#include "cli/report_files.hpp"
#include "runtime/diagnosis/diagnosis_html.hpp"
#include "runtime/diagnosis/diagnosis_report.hpp"
#include "runtime/fit/fit_report.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/io/output.hpp"

#include <fmt/format.h>

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
  int rounds = 3;           // refine
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
  add_report_options(app, o.report, true);
}

struct Prepared {
  lang::Program program;
  FitJob job;
  dx::ModelSource source;
  dx::DiagnoseSettings settings;
};

std::unique_ptr<Prepared> prepare(const DiagnoseOptions& o) {
  check_report_targets(o.report);
  auto p = std::make_unique<Prepared>();
  const std::string text = lang::read_source(o.fit.file);  // read once: diagnose edits the text compiled
  p->program = lang::compile_source(o.fit.file, text);
  std::vector<FitJob> jobs = fit_jobs(p->program, o.fit);
  if (jobs.size() != 1)
    throw runtime::UsageError(fmt::format("{} has {} fit blocks; choose the one to diagnose with --block N or --model NAME", o.fit.file, jobs.size()));
  p->job = std::move(jobs.front());
  p->source = {o.fit.file, text, p->job.model->name};
  p->settings.fit = p->job.settings;
  if (o.steps_per_cycle > 0) p->settings.fit.score.harmonic.steps_per_cycle = o.steps_per_cycle;
  else if (!p->job.steps_per_cycle_given) p->settings.fit.score.harmonic.steps_per_cycle = 128;
  // The candidates nest sliders and inerters, which `auto` would give to IDA; fixed steps are
  // exact for the sampled drive and much faster per point (docs/numerics.md).
  if (p->settings.fit.score.harmonic.solver == runtime::SolverChoice::automatic)
    p->settings.fit.score.harmonic.solver = runtime::SolverChoice::fixed;
  for (int i : p->job.free) p->settings.free.push_back(p->job.model->parameters[static_cast<std::size_t>(i)].path);
  p->settings.confirm = o.candidates;
  p->settings.standard_errors = o.report.any();  // the report's parameter table shows them
  p->settings.stage = [](const std::string& what) { std::cerr << "rheo: " << what << "\n"; };
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
      "leading ones and names the effect whose element earns its parameters (BIC), or `none`. See docs/cli.md.");
  return [o] {
    const auto p = prepare(*o);
    const dx::Diagnosis d = dx::diagnose(p->source, p->job.data, p->settings);
    if (!o->fit.output.empty()) {
      runtime::write_output(o->fit.output, d.refined_text);
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
  app.add_option("--rounds", o->rounds, "Most diagnose-add-refit rounds; default 3")->check(CLI::Range(1, 20));
  app.footer(
      "Repeats `rheo diagnose` on its own refined model until the effect is `none` or the rounds are spent, printing\n"
      "the gap after every round, and writes the final model. See docs/cli.md.");
  return [o] {
    const auto p = prepare(*o);
    const std::string output = o->fit.output.empty() ? default_refined_path(o->fit.file) : o->fit.output;
    dx::ModelSource source = p->source;
    dx::DiagnoseSettings settings = p->settings;
    bool interrupted = false;
    std::vector<dx::Diagnosis> rounds;
    for (int round = 1; round <= o->rounds; ++round) {
      const dx::Diagnosis& d = rounds.emplace_back(dx::diagnose(source, p->job.data, settings));
      if (round == 1) std::cout << fmt::format("rheo refine: model {} from {}; gap measure {}\n", source.model, o->fit.file, d.gap_name);
      std::cout << fmt::format("  round {}: {} = {:.4g} -> {:.4g}  effect {}{}\n", round, d.gap_name, d.gap_before, d.gap_after,
                               dx::effect_name(d.effect), d.added_element.empty() ? "" : fmt::format(", added '{}'", d.added_element))
                << std::flush;
      if (d.after)
        for (const std::string& note : runtime::bound_notes(*d.after)) std::cout << "    " << note << "\n";
      source.text = d.refined_text;
      if (d.after) settings.free = free_paths(*d.after);  // the added element's parameters join; a replaced one's leave
      interrupted = d.interrupted;
      if (d.effect == dx::Effect::none || interrupted) break;
      if (round == o->rounds) std::cout << fmt::format("  stopped after {} rounds (--rounds); the last model may still miss an effect\n", round);
    }
    runtime::write_output(output, source.text);
    std::cerr << fmt::format("rheo: final model {} written to {}\n", source.model, output);
    write_report(*o, *p, rounds, "rheo refine");
    return interrupted ? exit_code_interrupted : runtime::exit_code::ok;
  };
}

}  // namespace rheo::cli
