#include "cli/fit_job.hpp"

#include "cli/data_option.hpp"
#include "cli/program_lookup.hpp"
#include "cli/progress.hpp"
#include "lang/units.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/io/output.hpp"
#include "runtime/fit/yeoh_mean_curve.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <iostream>

namespace rheo::cli {
namespace {

std::atomic<bool> interrupt_requested{false};

extern "C" void on_interrupt(int) { interrupt_requested.store(true); }

// The NLopt algorithm an `optimizer` names; nullopt for `default` (the staged strategy of
// fit_search.hpp).
std::optional<runtime::Algorithm> algorithm_of(lang::Optimizer optimizer) {
  switch (optimizer) {
    case lang::Optimizer::automatic: return std::nullopt;
    case lang::Optimizer::bobyqa: return runtime::Algorithm::bobyqa;
    case lang::Optimizer::sbplx: return runtime::Algorithm::sbplx;
    case lang::Optimizer::neldermead: return runtime::Algorithm::neldermead;
    case lang::Optimizer::direct_l: return runtime::Algorithm::direct_l;
    case lang::Optimizer::crs2: return runtime::Algorithm::crs2;
    case lang::Optimizer::isres: return runtime::Algorithm::isres;
    case lang::Optimizer::mlsl: return runtime::Algorithm::mlsl;
  }
  return std::nullopt;
}

// A word given on the command line (--method, --optimizer), or the usage error listing the words.
template <class E>
E named_on_command_line(const std::string& word, std::optional<E> (*named)(std::string_view), const std::vector<std::string>& words,
                        const char* what) {
  if (auto value = named(word)) return *value;
  const std::vector<std::string> all_but_last(words.begin(), words.end() - 1);
  throw runtime::UsageError(fmt::format("unknown {} '{}'; use {} or {}", what, word, fmt::join(all_but_last, ", "), words.back()));
}

// A duration written on the command line, "60", "60s", "2 min", "500 ms" (a number and a time
// unit; seconds without one), in seconds; or the usage error.
double duration_in_seconds(const std::string& text, const char* option) {
  const std::size_t begin = text.find_first_not_of(' ');
  double value = 0.0;
  const char* first = text.data() + (begin == std::string::npos ? text.size() : begin);
  const char* last = text.data() + text.size();
  const auto [end, error] = std::from_chars(first, last, value);
  std::string_view unit(end, static_cast<std::size_t>(last - end));
  while (!unit.empty() && unit.front() == ' ') unit.remove_prefix(1);
  while (!unit.empty() && unit.back() == ' ') unit.remove_suffix(1);
  const std::optional<lang::Unit> parsed = unit.empty() ? lang::Unit{lang::dim::time, 1.0} : lang::parse_unit(unit);
  if (error != std::errc{} || !parsed || parsed->dimension != lang::dim::time || !(value > 0.0) || !std::isfinite(value * parsed->scale))
    throw runtime::UsageError(fmt::format("{} '{}': give a positive duration, e.g. 60s, 90 s or 5 min", option, text));
  return value * parsed->scale;
}

// Block settings first, then the command line over them.
void configure(FitJob& job, const lang::FitDirective* block, const FitOptions& o) {
  const lang::FitSettings given = block ? block->settings : lang::FitSettings{};
  runtime::FitSettings& s = job.settings;
  s.score.objective = given.objective;
  job.description.objective = lang::word_of(given.objective);
  if (given.stiffness_weight) {
    s.score.stiffness_weight = *given.stiffness_weight;
    s.score.damping_weight = 1.0 - *given.stiffness_weight;
  }
  s.score.method = o.method.empty() ? given.method : named_on_command_line(o.method, lang::fit_method_named, lang::fit_method_words(), "method");
  job.description.method = lang::word_of(s.score.method);
  const lang::Optimizer optimizer = o.optimizer.empty()
                                        ? given.optimizer
                                        : named_on_command_line(o.optimizer, lang::optimizer_named, lang::optimizer_words(), "optimizer");
  job.description.optimizer = lang::word_of(optimizer);
  s.search.algorithm = algorithm_of(optimizer);
  s.search.max_evaluations = o.max_evaluations > 0 ? o.max_evaluations : given.max_evaluations.value_or(s.search.max_evaluations);
  s.search.starts = o.starts > 0 ? o.starts : given.starts.value_or(s.search.starts);
  s.search.seed = o.seed >= 0 ? static_cast<unsigned long>(o.seed) : static_cast<unsigned long>(given.seed);
  s.search.tolerance = given.tolerance.value_or(s.search.tolerance);
  s.time_limit = o.time_limit.empty() ? given.time_limit : duration_in_seconds(o.time_limit, "--time-limit");
  job.description.seed = s.search.seed;
  s.score.harmonic.definition = given.definition;
  s.score.harmonic.steps_per_cycle = given.steps_per_cycle.value_or(s.score.harmonic.steps_per_cycle);
  job.steps_per_cycle_given = given.steps_per_cycle.has_value();
  // Periodicity to 1e-6 is far inside any measurement's noise, and a third of the cycles of 1e-9.
  s.score.harmonic.tolerance = 1e-6;
  s.score.harmonic.solver = given.solver;
  s.score.harmonic.threads = o.threads;
  if (o.max_evaluations < 0 || o.starts < 0) throw runtime::UsageError("--max-evaluations and --starts must be positive");
}

// --yeoh-start: the yeoh spring's start values from the mean curve of the largest loop of a
// static or quasi-static history, by least squares (eqs. 5.28-5.32), clamped into its bounds.
// Only free constants are started (a fixed one keeps its value, as the fitted file does), and
// the file given replaces the automatic start from a history among the data.
void set_yeoh_start(FitJob& job, const std::string& path) {
  const lang::CheckedModel& model = *job.model;
  const lang::Element* yeoh = nullptr;
  for (const auto& e : model.root.children)
    if (e.kind == lang::ElementKind::yeoh) {
      if (yeoh)
        throw runtime::UsageError(fmt::format("--yeoh-start: model '{}' has several yeoh springs ('{}', '{}'); the mean curve can start only one",
                                              model.name, yeoh->path, e.path));
      yeoh = &e;
    }
  if (!yeoh) throw runtime::UsageError(fmt::format("--yeoh-start: model '{}' has no yeoh spring in its root block to start", model.name));
  const runtime::LoopSamples record = runtime::loop_samples_from_table(runtime::read_table(path));  // errors name file:row
  const std::array<int, 3> constants{yeoh->parameters.at(0), yeoh->parameters.at(1), yeoh->parameters.at(2)};
  std::array<runtime::YeohStartValue, 3> started;
  try {
    started = runtime::yeoh_start_values(model, constants, job.free, record);
  } catch (const runtime::DataError& e) {
    throw runtime::DataError(
        fmt::format("{}: --yeoh-start: {}; give a static loop record (displacement and force over at least one "
                    "full cycle, as specimen_D_static.csv)",
                    path, e.what()));
  }
  if (job.start_values.empty())
    for (const auto& p : model.parameters) job.start_values.push_back(p.value);
  job.settings.yeoh_start_from_history = false;
  for (const runtime::YeohStartValue& s : started) {
    const lang::Parameter& p = model.parameters.at(static_cast<std::size_t>(s.parameter));
    if (!s.free) {
      job.notes += fmt::format("rheo: --yeoh-start {}: {} is not free and keeps its value\n", path, p.path);
      continue;
    }
    job.start_values[static_cast<std::size_t>(s.parameter)] = s.value;
    job.notes += fmt::format(
        "rheo: --yeoh-start {}: {} = {:.6g} {} (least squares on the mean curve, eq. 5.32){}\n", path, p.path, runtime::in_written_unit(p, s.value),
        runtime::written_unit(p),
        s.value != s.unclamped ? fmt::format(", clamped into its bounds from {:.6g}", runtime::in_written_unit(p, s.unclamped)) : std::string());
  }
}

}  // namespace

InterruptScope::InterruptScope() {
  interrupt_requested.store(false);
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  action.sa_flags = static_cast<int>(SA_RESETHAND);  // glibc defines it as an unsigned 0x80000000
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &previous_);
}

InterruptScope::~InterruptScope() { sigaction(SIGINT, &previous_, nullptr); }

const std::atomic<bool>* InterruptScope::flag() const { return &interrupt_requested; }

double duration_option(const std::string& text, const char* option) { return duration_in_seconds(text, option); }

std::vector<FitJob> fit_jobs(const lang::Program& program, const FitOptions& o) {
  std::vector<FitJob> jobs;
  auto add = [&](const lang::CheckedModel& model, const lang::FitDirective* block) {
    FitJob job;
    job.model = &model;
    job.free = block ? block->free : lang::default_free_parameters(model);
    if (job.free.empty())
      throw runtime::UsageError(
          fmt::format("model '{}' has no parameter with bounds; give bounds to the ones to fit, e.g. `k = 300 N/mm in [10, 5000]`", model.name));
    job.description.source = o.file;
    job.progress_lines = o.progress;
    configure(job, block, o);
    if (!o.data.empty()) {
      for (const auto& text : o.data) job.data.push_back(read_data_option(text));
    } else if (block) {
      for (const auto& d : block->data)
        job.data.push_back(runtime::read_fit_data(relative_to(o.file, d.file), d.weight, &d.where, runtime::reading_of(d)));
      job.lines = block->data;
      job.lines_block = static_cast<int>(block - program.fits.data());
    }
    if (job.data.empty())
      throw runtime::UsageError(
          fmt::format("no data to fit model '{}' to; give --data FILE.csv or add `data \"FILE.csv\"` to its fit block", model.name));
    job.output = !o.output.empty() ? o.output : block ? relative_to(o.file, block->output) : std::string();
    runtime::check_output_destination(job.output);  // before the search, not after it
    if (!o.yeoh_start.empty()) set_yeoh_start(job, o.yeoh_start);
    jobs.push_back(std::move(job));
  };
  if (o.block > static_cast<int>(program.fits.size()))
    throw runtime::UsageError(fmt::format("--block {}: {} has {} fit block(s)", o.block, o.file, program.fits.size()));
  for (std::size_t k = 0; k < program.fits.size(); ++k) {
    const lang::FitDirective& block = program.fits[k];
    if ((o.model.empty() || block.model == o.model) && (o.block == 0 || o.block == static_cast<int>(k) + 1))
      add(*program.find_model(block.model), &block);
  }
  if (jobs.empty()) {
    if (!program.fits.empty())
      throw runtime::UsageError(fmt::format("{} has no fit block for model '{}'{}", o.file, o.model,
                                            o.block > 0 ? fmt::format(" at --block {}", o.block) : std::string()));
    add(chosen_model(program, o.file, o.model, "to fit", "choose one with --model or write a fit block"), nullptr);
  }
  return jobs;
}

runtime::FitResult run_fit_job(const FitJob& job) {
  runtime::FitSettings settings = job.settings;
  const std::shared_ptr<Progress> progress = Progress::start(job.progress_lines, settings.time_limit);
  progress->label(fmt::format("fit {}", job.model->name));
  progress->announce_budget();
  settings.progress = Progress::evaluation_callback(progress);
  InterruptScope interrupt_scope;
  settings.interrupt = interrupt_scope.flag();
  std::cerr << job.notes;
  runtime::Network start = runtime::Network::compile(*job.model);
  if (!job.start_values.empty()) start = start.with_parameters(job.start_values);
  runtime::FitResult result = runtime::fit(start, job.free, job.data, settings);
  progress->finish();
  return result;
}

}  // namespace rheo::cli
