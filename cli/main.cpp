// rheo: a language and interpreter for 1-D rheological networks of rubber bushings.
// Exit codes: 0 ok, 1 internal error, 2 usage, 3 model file, 4 data or I/O, 5 numerical, 130 interrupted fit, diagnose or refine.
#include "lang/diagnostics.hpp"
#include "lang/frontend.hpp"
#include "cli/commands.hpp"
#include "cli/usage_errors.hpp"
#include "runtime/core/errors.hpp"

#include <fmt/format.h>

#include <iostream>

int main(int argc, char** argv) {
  using namespace rheo;
  CLI::App app{
      "rheo: model rubber bushings as 1-D rheological networks.\n"
      "Exit codes: 0 ok, 1 internal error, 2 usage, 3 model file error, 4 data or I/O error,\n"
      "5 numerical (e.g. a harmonic point did not reach steady state; results are still written),\n"
      "130 a fit, diagnose or refine stopped by Ctrl-C (its best result so far is still written)."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "rheo " RHEO_VERSION);  // project(VERSION) in CMakeLists.txt
  std::vector<std::pair<CLI::App*, cli::Command>> commands;
  auto* check = app.add_subcommand("check", "Parse and check a .rheo file; report every error found");
  commands.emplace_back(check, cli::add_check_command(*check));
  auto* simulate = app.add_subcommand("simulate", "Run the protocols of a .rheo file's simulate blocks");
  commands.emplace_back(simulate, cli::add_simulate_command(*simulate));
  auto* fit = app.add_subcommand("fit", "Identify a model's bounded parameters from measured data (NLopt)");
  commands.emplace_back(fit, cli::add_fit_command(*fit));
  auto* report = app.add_subcommand("report", "Write an HTML report: a model against measured data or its simulated results");
  commands.emplace_back(report, cli::add_report_command(*report));
  auto* diagnose = app.add_subcommand("diagnose", "Name the effect a model misses in measured data, add the element for it and refit");
  commands.emplace_back(diagnose, cli::add_diagnose_command(*diagnose));
  auto* refine = app.add_subcommand("refine", "Repeat diagnose, add and refit until nothing is missing; write the final model");
  commands.emplace_back(refine, cli::add_refine_command(*refine));
  auto* exporter = app.add_subcommand(
      "export",
      "Write a model for other tools: a Functional Mock-up Unit for co-simulation (--fmu), Abaqus and ANSYS viscoelastic material cards (--abaqus, --ansys)");
  commands.emplace_back(exporter, cli::add_export_command(*exporter));
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help and --version (CallForHelp, CallForVersion): CLI11 prints them, exit 0
    return app.exit(e);
  } catch (const CLI::ParseError& e) {  // a usage error, in rheo's words (docs/errors.md#usage-errors)
    std::cerr << "rheo: error: " << cli::usage_message(app, e, std::vector<std::string>(argv + 1, argv + argc)) << "\n";
    return runtime::exit_code::usage;
  }
  try {
    for (auto& [sub, run] : commands)
      if (sub->parsed()) return run();
  } catch (const lang::CompileError& e) {
    std::cerr << e.what();  // every diagnostic, each ending in a newline
    return exit_code_of(e);
  } catch (const UsageError& e) {
    std::cerr << "rheo: error: " << e.what() << "\n";
    return exit_code_of(e);
  } catch (const NumericalError& e) {
    std::cerr << "rheo: numerical error: " << e.what() << "\n";
    return exit_code_of(e);
  } catch (const UserError& e) {  // model and data errors: "file:line:col: error: ..." naming the element or cell
    std::cerr << e.what() << "\n";
    return exit_code_of(e);
  } catch (const std::exception& e) {  // any other exception is a bug, whatever the input
    std::cerr << "rheo: internal error: " << e.what() << "\nPlease report this with the input that caused it.\n";
    return exit_code_of(e);
  }
  return runtime::exit_code::internal;
}
