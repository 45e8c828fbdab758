#include "lang/diagnostics.hpp"
#include "lang/frontend.hpp"
#include "lang/names.hpp"
#include "lang/protocol_schema.hpp"
#include "lang/text_encoding.hpp"
#include "cli/commands.hpp"
#include "cli/progress.hpp"
#include "cli/report_files.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/network/network.hpp"
#include "runtime/io/hdf5_history.hpp"
#include "runtime/io/hdf5_writer.hpp"
#include "runtime/io/history_writer.hpp"
#include "runtime/io/matlab_file.hpp"
#include "runtime/io/output.hpp"
#include "runtime/protocols/run_protocols.hpp"
#include "runtime/protocols/stream_history.hpp"
#include "runtime/report/history_digest.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

namespace rheo::cli {
namespace {

struct Options {
  std::string file;
  std::string output;
  std::string model;
  std::string protocol;
  std::vector<std::string> settings;
  bool json = false;
  bool elements = false;
  std::optional<lang::SolverChoice> solver;
  int threads = 1;
  ReportTargets report;
};

void apply_overrides(lang::Protocol& protocol, const Options& o) {
  for (const auto& text : o.settings) {
    try {
      lang::override_setting(protocol, lang::parse_setting(protocol.kind, text));
    } catch (const lang::CompileError& e) {
      throw runtime::UsageError(fmt::format("--set '{}' for protocol {}:\n{}", lang::printable(text), lang::protocol_name(protocol.kind), e.what()));
    }
  }
  lang::CommonSettings& common = lang::common(protocol.settings);
  if (o.solver) common.solver = *o.solver;
  if (o.json) common.format = lang::OutputFormat::json;
  if (o.elements) common.elements = true;
}

// Why no protocol of the file runs: no simulate block, a --model or --protocol that is
// misspelt (naming the nearest), or one the file's simulate blocks do not have.
runtime::UsageError nothing_to_run(const lang::Program& program, const Options& o) {
  if (!o.protocol.empty() && !lang::protocol_kind(o.protocol))
    return runtime::UsageError(fmt::format("unknown protocol '{}' for --protocol;{} the protocols are {}", lang::printable(o.protocol),
                                           lang::did_you_mean(o.protocol, lang::protocol_names()), lang::join(lang::protocol_names())));
  std::vector<std::string> models, kinds;
  for (const auto& sim : program.simulations) {
    if (std::find(models.begin(), models.end(), sim.model) == models.end()) models.push_back(sim.model);
    if (!o.model.empty() && sim.model != o.model) continue;
    for (const auto& protocol : sim.protocols)
      if (const std::string kind = lang::protocol_name(protocol.kind); std::find(kinds.begin(), kinds.end(), kind) == kinds.end())
        kinds.push_back(kind);
  }
  if (program.simulations.empty())
    return runtime::UsageError(fmt::format(
        "{} has no simulate block; add one, e.g.\n  simulate {{\n    harmonic frequency = 1 Hz .. 51 Hz step 2 Hz, amplitude = [0.2, 1.0] mm\n  }}",
        o.file));
  if (!o.model.empty() && std::find(models.begin(), models.end(), o.model) == models.end())
    return runtime::UsageError(fmt::format("{} has no simulate block of model '{}' (--model);{} its simulate blocks are of {}", o.file,
                                           lang::printable(o.model), lang::did_you_mean(o.model, models), lang::join(models)));
  return runtime::UsageError(fmt::format("{} has no {} protocol{}; its protocols are {}", o.file, o.protocol,
                                         o.model.empty() ? "" : fmt::format(" for model '{}'", o.model), lang::join(kinds)));
}

// A protocol's result, held (RESULT) or written to a file not yet in place: streamed as CSV
// (PENDING), or as HDF5 (HDF5, streamed or from RESULT).
struct Outcome {
  std::optional<runtime::ProtocolResult> result;
  std::unique_ptr<runtime::PendingOutput> pending;
  std::unique_ptr<runtime::Hdf5HistoryWriter> hdf5;
  std::uint64_t size = 0;  // points or samples
  std::string notes;
  int not_converged = 0;
};

struct Job {
  const lang::CheckedModel* model;
  lang::Protocol protocol;
};

// Whether the result goes to an HDF5 file (by the destination's extension, runtime/io/hdf5_writer.hpp).
// HDF5, or MATLAB's v7.3 MAT-file, which is HDF5 with MATLAB's header (hdf5_writer.hpp).
bool hdf5_destination(const std::string& destination) { return runtime::is_hdf5_name(destination) || runtime::is_matlab_name(destination); }

// Histories stream where they are written as CSV or HDF5 (JSON holds whole arrays); a report
// draws a streamed history from its digest (report/history_digest.hpp).
bool streamed(const lang::Protocol& protocol, const std::string& destination) {
  return runtime::streams(protocol) && (lang::common(protocol.settings).format == lang::OutputFormat::csv || hdf5_destination(destination));
}

// DIGEST, when not null, also receives the history, for a report.
Outcome run_streamed(const runtime::Network& network, const Job& job, const std::string& destination, const std::string& source_file,
                     runtime::HistorySink* digest) {
  Outcome outcome;
  std::optional<runtime::HistoryCsvWriter> csv;
  if (hdf5_destination(destination)) {
    outcome.hdf5 = std::make_unique<runtime::Hdf5HistoryWriter>(destination);
  } else {
    outcome.pending = std::make_unique<runtime::PendingOutput>(destination);
    csv.emplace(*outcome.pending);
  }
  runtime::HistorySink& writer = csv ? static_cast<runtime::HistorySink&>(*csv) : *outcome.hdf5;
  std::optional<runtime::TeeSink> both;
  if (digest) both.emplace(writer, *digest);
  runtime::HistorySink& sink = both ? static_cast<runtime::HistorySink&>(*both) : writer;
  const auto progress = Progress::start(false, std::nullopt);
  progress->label(fmt::format("history of model {}", job.model->name));
  const runtime::StreamedHistory run = runtime::stream_history(network, job.protocol, source_file, sink, Progress::stream_callback(progress));
  progress->finish();
  if (csv) csv->finish();
  outcome.size = run.samples;
  outcome.notes = run.notes;
  return outcome;
}

}  // namespace

Command add_simulate_command(CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("file", o->file, "The .rheo file")->required();
  app.add_option("-o,--output", o->output, "Write the result here ('-' for standard output); needs exactly one protocol to run");
  app.add_option("--model", o->model, "Run only the simulate blocks of this model");
  app.add_option("--protocol", o->protocol, "Run only protocols of this kind (harmonic, static, quasistatic, history, step)");
  app.add_option("--set", o->settings,
                 "Override a protocol setting, in the file's syntax, e.g. --set 'amplitude = [0.1, 1] mm' "
                 "--set 'frequency = 1 Hz .. 20 Hz step 1 Hz' --set 'steps_per_cycle = 4096'");
  app.add_flag("--json", o->json, "Write JSON instead of CSV");
  app.add_flag("--elements", o->elements, "Time histories: add every element's force and elongation");
  app.add_option_function<std::string>(
         "--solver", [o](const std::string& word) { o->solver = lang::solver_choice_named(word); },
         "auto | fixed | sundials: the integrator of every protocol (overrides `solver =` in the file); "
         "auto takes SUNDIALS IDA for networks with an inerter or blocks alternating more than 3 deep, "
         "the fixed-step kernels otherwise")
      ->check(CLI::IsMember(lang::solver_choice_words()));
  app.add_option("--threads", o->threads, "Harmonic grid points simulated at once (0: every hardware thread); results do not depend on it; default 1")
      ->check(CLI::Range(0, 1024));
  add_report_options(app, o->report, true);
  app.footer(
      "Results go where each protocol's `output \"FILE\"` line says (relative to the .rheo file), "
      "else to standard output.");
  return [o] {
    const lang::Program program = lang::load_program(o->file);
    std::vector<Job> jobs;
    for (const auto& sim : program.simulations) {
      if (!o->model.empty() && sim.model != o->model) continue;
      for (const auto& protocol : sim.protocols) {
        if (!o->protocol.empty() && o->protocol != lang::protocol_name(protocol.kind)) continue;
        jobs.push_back({program.find_model(sim.model), protocol});
      }
    }
    if (jobs.empty()) throw nothing_to_run(program, *o);
    if (!o->output.empty() && jobs.size() != 1)
      throw runtime::UsageError(fmt::format("-o names one output but {} protocols would run; select one with --protocol or --model", jobs.size()));
    if (o->report.any())
      for (const auto& job : jobs)
        if (job.model != jobs.front().model)
          throw runtime::UsageError(fmt::format("--report and --plot show one model, but models {} and {} would run; select one with --model",
                                                jobs.front().model->name, job.model->name));
    // Every destination is checked before anything runs, and every protocol runs before any
    // output is put in place: a bad path, a later protocol's bad data file or a numerical
    // failure leaves every earlier output intact. A history streamed (stream_history.hpp) is
    // written as it runs, to a PendingOutput that only the end puts in place.
    std::vector<std::string> destinations;
    for (const auto& job : jobs) {
      std::string destination = o->output;
      if (destination.empty() && !job.protocol.output.empty())
        destination = (std::filesystem::path(o->file).parent_path() / job.protocol.output).string();
      runtime::check_output_destination(destination);
      if (hdf5_destination(destination) && job.protocol.kind == lang::ProtocolKind::harmonic)
        throw runtime::UsageError(
            fmt::format("{}: {} output holds a time history; write the harmonic protocol's result as CSV or JSON "
                        "(e.g. -o result.csv)",
                        destination, runtime::is_matlab_name(destination) ? "a MATLAB" : "an HDF5"));
      if (hdf5_destination(destination) && (o->json || lang::common(job.protocol.settings).format == lang::OutputFormat::json))
        throw runtime::UsageError(fmt::format(
            "{}: the output is {} but JSON is asked for (--json or format = json); "
            "drop one",
            destination, runtime::is_matlab_name(destination) ? "a MATLAB file (its name ends in .mat)" : "HDF5 (its name ends in .h5)"));
      destinations.push_back(std::move(destination));
    }
    check_report_targets(o->report);
    std::optional<runtime::report::ReportContent> report;
    std::vector<Outcome> outcomes;
    for (std::size_t k = 0; k < jobs.size(); ++k) {
      auto& job = jobs[k];
      apply_overrides(job.protocol, *o);
      const runtime::Network network = runtime::Network::compile(*job.model);
      const std::string label = fmt::format("{} protocol ({}:{})", lang::protocol_name(job.protocol.kind), job.protocol.where.file,
                                            job.protocol.where.line);
      if (o->report.any() && !report) report = runtime::report::report_for_model(network, o->file, "rheo simulate");
      if (streamed(job.protocol, destinations[k])) {
        std::optional<runtime::report::HistoryDigest> digest;
        if (report) digest.emplace();
        outcomes.push_back(run_streamed(network, job, destinations[k], o->file, digest ? &*digest : nullptr));
        if (digest) report->histories.push_back(digest->comparison(label));
        continue;
      }
      runtime::ProtocolResult result = runtime::run_protocol(network, job.protocol, o->file, o->threads);
      if (report) runtime::report::add_simulation_result(*report, label, result);
      Outcome outcome;
      if (hdf5_destination(destinations[k])) {  // a history held whole (SUNDIALS), written now, put in place at the end
        const auto& history = std::get<runtime::History>(result.data);
        outcome.hdf5 = std::make_unique<runtime::Hdf5HistoryWriter>(destinations[k]);
        outcome.hdf5->begin(result.header, history.element_paths);
        outcome.hdf5->write(history);
      }
      outcome.size = static_cast<std::uint64_t>(result.size());
      outcome.notes = result.notes;
      outcome.not_converged = result.not_converged;
      outcome.result = std::move(result);
      outcomes.push_back(std::move(outcome));
    }
    int not_converged = 0;
    for (std::size_t k = 0; k < jobs.size(); ++k) {
      const auto& job = jobs[k];
      Outcome& outcome = outcomes[k];
      const std::string& destination = destinations[k];
      if (outcome.hdf5) outcome.hdf5->commit();
      else if (outcome.pending) outcome.pending->commit();
      else runtime::write_output(destination, runtime::rendered(*outcome.result, lang::common(job.protocol.settings).format));
      std::cerr << outcome.notes;
      if (!destination.empty() && destination != "-")
        std::cerr << fmt::format("rheo: {} of model {}: {} {} written to {}\n", lang::protocol_name(job.protocol.kind), job.model->name,
                                 outcome.size, job.protocol.kind == lang::ProtocolKind::harmonic ? "points" : "samples", destination);
      not_converged += outcome.not_converged;
    }
    if (report) write_report_files(*report, o->report);
    if (not_converged > 0) {
      std::cerr << fmt::format("rheo: {} harmonic point(s) did not reach steady state (column 'converged' = 0)\n", not_converged);
      return runtime::exit_code::numerical;
    }
    return runtime::exit_code::ok;
  };
}

}  // namespace rheo::cli
