#include "lang/frontend.hpp"
#include "cli/commands.hpp"
#include "runtime/dae/dae_graph.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/network/network.hpp"
#include "runtime/protocols/solver_choice.hpp"

#include <fmt/format.h>

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
    std::cout << fmt::format("{}: ok: {} model(s), {} parameter(s), {} simulate block(s)\n", options->file, program.models.size(), parameters,
                             program.simulations.size())
              << graphs;
    return 0;
  };
}

}  // namespace rheo::cli
