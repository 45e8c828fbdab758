#include "lang/frontend.hpp"
#include "cli/commands.hpp"
#include "cli/program_lookup.hpp"
#include "runtime/dae/dae_graph.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/network/network.hpp"
#include "runtime/protocols/solver_choice.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>

namespace rheo::cli {
namespace {

// Whether a run of the file certainly integrates MODEL with SUNDIALS IDA: a simulate protocol
// that takes IDA (a harmonic one only where no closed form serves it, harmonic.hpp), or a fit
// block that names solver = sundials (with `auto` a fit's data decide, which check does not
// read). check then raises what those runs would (dae_graph.hpp).
bool runs_on_sundials(const lang::Program& program, const runtime::Network& network) {
  const std::string& model = network.model().name;
  for (const auto& simulation : program.simulations) {
    if (simulation.model != model) continue;
    for (const auto& protocol : simulation.protocols) {
      const runtime::SolverChoice choice = lang::common(protocol.settings).solver;
      if (!runtime::uses_sundials(network, choice)) continue;
      const auto* harmonic = std::get_if<lang::HarmonicSettings>(&protocol.settings);
      if (!harmonic) return true;
      runtime::HarmonicOptions options;
      options.solver = choice;
      if (harmonic->steady_state == runtime::SteadyState::time_stepping) options.steady_state = runtime::SteadyState::time_stepping;
      if (!runtime::uses_closed_form(network, options)) return true;
    }
  }
  for (const auto& fit : program.fits)
    if (fit.model == model && fit.settings.solver == runtime::SolverChoice::sundials) return true;
  return false;
}

// A note per data or history file the program reads that does not exist (resolved as the
// runs resolve it: relative to the .rheo file), `FILE:LINE:COL: warning: ...`. Not an error: a
// file may name data that a simulate block or a rig writes later.
std::string missing_file_notes(const lang::Program& program, const std::string& rheo_file) {
  std::string notes;
  auto note = [&](const std::string& name, const lang::SourceLocation& where, const char* what) {
    const std::string path = relative_to(rheo_file, name);
    if (std::filesystem::exists(path)) return;
    notes += fmt::format("{}:{}:{}: warning: {} '{}' does not exist (looked for {}); fit, report and simulate will fail on it until it does\n",
                         where.file, where.line, where.column, what, name, path);
  };
  for (const auto& fit : program.fits)
    for (const auto& data : fit.data) note(data.file, data.where, "data file");
  for (const auto& simulation : program.simulations)
    for (const auto& protocol : simulation.protocols)
      if (const auto* history = std::get_if<lang::HistorySettings>(&protocol.settings)) note(history->file, history->file_where, "history file");
  return notes;
}

}  // namespace

Command add_check_command(CLI::App& app) {
  struct Options {
    std::string file;
    bool graph = false;
  };
  auto options = std::make_shared<Options>();
  app.add_option("file", options->file, "The .rheo file")->required();
  app.add_flag("--graph", options->graph, "Print the compiled network of every model");
  return [options] {
    const lang::Program program = lang::load_program(options->file);
    std::size_t parameters = 0;
    for (const auto& model : program.models) parameters += model.parameters.size();
    std::string graphs;  // every model compiles (or the check fails) before "ok" is printed
    for (const auto& model : program.models) {
      const runtime::Network network = runtime::Network::compile(model);
      if (runs_on_sundials(program, network)) (void)runtime::DaeGraph::build(network);  // ModelError for what IDA cannot integrate
      if (options->graph) graphs += network.describe();
    }
    std::cerr << missing_file_notes(program, options->file);
    std::cout << fmt::format("{}: ok: {} model(s), {} parameter(s), {} simulate block(s)\n", options->file, program.models.size(), parameters,
                             program.simulations.size())
              << graphs;
    return 0;
  };
}

}  // namespace rheo::cli
