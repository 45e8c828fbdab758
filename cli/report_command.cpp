// `rheo report FILE [--data CSV]... [--model NAME] [-o REPORT.html] [--plot FIG.svg]`: the
// model against measured data (or its simulate protocols' results) as an HTML report; see
// docs/cli.md.
#include "lang/frontend.hpp"
#include "lang/protocol_schema.hpp"
#include "cli/commands.hpp"
#include "cli/data_option.hpp"
#include "cli/program_lookup.hpp"
#include "cli/progress.hpp"
#include "cli/report_files.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/fit/fit_scoring.hpp"
#include "runtime/fit/objective.hpp"
#include "runtime/protocols/run_protocols.hpp"
#include "runtime/protocols/stream_history.hpp"
#include "runtime/report/history_digest.hpp"

#include <fmt/format.h>

#include <memory>

namespace rheo::cli {
namespace {

namespace report = runtime::report;

struct Options {
  std::string file, model;
  std::vector<std::string> data;
  ReportTargets targets;
  int threads = 1;
};

// Data to compare the model with, and how its harmonic points are simulated: the settings of
// the fit block the data belong to (definition, solver, steps per cycle), so that the report
// scores the model as `rheo fit` does (#22 item 3).
struct ReportData {
  runtime::FitDataSet set;
  runtime::HarmonicOptions options;
};

runtime::HarmonicOptions harmonic_options_of(const lang::FitDirective* block, int threads) {
  runtime::HarmonicOptions options;
  options.threads = threads;
  if (block == nullptr) return options;
  options.definition = block->settings.definition;
  options.solver = block->settings.solver;
  options.steps_per_cycle = block->settings.steps_per_cycle.value_or(options.steps_per_cycle);
  options.tolerance = 1e-6;  // as the fit scores (cli/fit_job.cpp)
  return options;
}

// The model simulated at every point of every data file.
void add_data(report::ReportContent& content, const runtime::Network& network, const std::vector<ReportData>& data) {
  for (const auto& [set, options] : data) {
    const runtime::Prediction p = runtime::predict(network, set, runtime::FitMethod::exact, options, nullptr);
    if (set.is_harmonic()) {
      content.harmonic.push_back(report::compare_harmonic(set.harmonic(), p.points, set.source));
      content.notes.insert(content.notes.end(), set.harmonic().notes.begin(), set.harmonic().notes.end());
      for (std::string& note : runtime::damping_left_out(set.harmonic())) content.notes.push_back(std::move(note));
    } else content.histories.push_back(report::compare_history(set, p));
  }
}

// The results of the model's simulate protocols, whatever format they would be written in. A
// history is streamed into a digest (report/history_digest.hpp): a
// long one is drawn in constant memory, without the limits of a history held whole.
void add_protocols(report::ReportContent& content, const runtime::Network& network, const lang::Program& program, const Options& o) {
  for (const auto& sim : program.simulations) {
    if (sim.model != network.model().name) continue;
    for (lang::Protocol protocol : sim.protocols) {
      lang::common(protocol.settings).elements = false;  // the report draws the whole network's force
      const std::string label = fmt::format("{} protocol ({}:{})", lang::protocol_name(protocol.kind), protocol.where.file, protocol.where.line);
      if (runtime::streams(protocol)) {
        report::HistoryDigest digest;
        const auto progress = Progress::start(false, std::nullopt);
        progress->label(fmt::format("history of model {}", network.model().name));
        runtime::stream_history(network, protocol, o.file, digest, Progress::stream_callback(progress));
        progress->finish();
        content.histories.push_back(digest.comparison(label));
        continue;
      }
      report::add_simulation_result(content, label, runtime::run_protocol(network, protocol, o.file, o.threads));
    }
  }
}

std::vector<ReportData> fit_block_data(const lang::Program& program, const std::string& model, const std::string& file, int threads) {
  std::vector<ReportData> data;
  for (const auto& block : program.fits) {
    if (block.model != model) continue;
    for (const auto& d : block.data)
      data.push_back(
          {runtime::read_fit_data(relative_to(file, d.file), d.weight, &d.where, runtime::reading_of(d)), harmonic_options_of(&block, threads)});
  }
  return data;
}

// The first fit block of MODEL, whose settings --data is scored with; null when there is none.
const lang::FitDirective* first_fit_block(const lang::Program& program, const std::string& model) {
  for (const auto& block : program.fits)
    if (block.model == model) return &block;
  return nullptr;
}

}  // namespace

Command add_report_command(CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("file", o->file, "The .rheo file")->required();
  app.add_option(
      "--data", o->data,
      std::string("Measured data (harmonic table or time history) to compare the model with: ") + data_option_settings_help + ". Repeatable");
  app.add_option("--model", o->model, "The model to report on (needed when the file defines several)");
  app.add_option("-o,--output", o->targets.html, "Write the HTML report here");
  add_report_options(app, o->targets, false);
  app.add_option("--threads", o->threads, "Harmonic points simulated at once (0: every hardware thread); default 1")->check(CLI::Range(0, 1024));
  app.footer(
      "Without --data the report shows the model's simulate protocols, or, when it has none, the data of its fit\n"
      "blocks. --data is relative to the working directory, data lines of fit blocks to the .rheo file. Harmonic\n"
      "points are simulated with the model's (first) fit block's definition, solver and steps per cycle.");
  return [o] {
    if (!o->targets.any()) throw runtime::UsageError("rheo report writes nothing without -o REPORT.html or --plot FIGURE.svg; add one");
    const lang::Program program = lang::load_program(o->file);
    const lang::CheckedModel& model = chosen_model(program, o->file, o->model, "to report on", "choose one with --model");
    const runtime::Network network = runtime::Network::compile(model);
    report::ReportContent content = report::report_for_model(network, o->file, "rheo report");
    if (!o->data.empty()) {
      std::vector<ReportData> data;
      for (const auto& text : o->data)
        data.push_back({read_data_option(text), harmonic_options_of(first_fit_block(program, model.name), o->threads)});
      add_data(content, network, data);
    } else {
      add_protocols(content, network, program, *o);
      if (content.harmonic.empty() && content.histories.empty())
        add_data(content, network, fit_block_data(program, model.name, o->file, o->threads));
    }
    if (content.harmonic.empty() && content.histories.empty())
      throw runtime::UsageError(
          fmt::format("model '{}' in {} has no simulate protocol and no fit data to report; give --data FILE.csv "
                      "or add a simulate block",
                      model.name, o->file));
    write_report_files(content, o->targets);
    return runtime::exit_code::ok;
  };
}

}  // namespace rheo::cli
