// `rheo export FILE`: a model written for other tools. --abaqus and --ansys write the material
// cards of its linear viscoelastic part (cli/fe_export.hpp).
#include "lang/frontend.hpp"
#include "cli/commands.hpp"
#include "cli/fe_export.hpp"
#include "cli/program_lookup.hpp"
#include "runtime/core/errors.hpp"

#include <memory>
#include <string>

namespace rheo::cli {
namespace {

struct Options {
  std::string file;
  std::string model;
  FeExportOptions fe;
};

}  // namespace

Command add_export_command(CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("file", o->file, "The .rheo file")->required();
  app.add_option("--model", o->model, "The model to export (default: the file's only model)");
  add_fe_export_options(app, o->fe);
  app.footer(
      "The Abaqus and ANSYS cards take a model whose branches are springs, maxwell elements (or a spring and a dashpot in "
      "series) and springpots acting side by side; any other branch is refused at its line:col, or left out by name with "
      "--leave-out. Destinations are checked before anything is computed, and nothing is written unless every file can be.");
  return [o] {
    if (!o->fe.any()) throw runtime::UsageError("nothing to export; give --abaqus OUT.inp and/or --ansys OUT.mac");
    check_fe_export_options(o->fe);
    const lang::Program program = lang::load_program(o->file);
    const lang::CheckedModel& model = chosen_model(program, o->file, o->model, "to export", "choose one with --model");
    return run_fe_export(o->file, program, model, o->fe);
  };
}

}  // namespace rheo::cli
