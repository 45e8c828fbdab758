#include "lang/frontend.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/network.hpp"

#include <fmt/format.h>

#include <iostream>
#include <memory>

namespace rheo::cli {

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
      if (options->graph) graphs += network.describe();
    }
    std::cout << fmt::format("{}: ok: {} model(s), {} parameter(s), {} simulate block(s)\n", options->file,
                             program.models.size(), parameters, program.simulations.size())
              << graphs;
    return 0;
  };
}

}  // namespace rheo::cli
