// `rheo export FILE`: a model written for other tools. --fmu writes it as a Functional Mock-up Unit
// for co-simulation (runtime/export/fmu_export.hpp); --abaqus and --ansys write the material cards
// of its linear viscoelastic part (cli/fe_export.hpp). docs/cli.md#rheo-export.
#include "lang/frontend.hpp"
#include "cli/commands.hpp"
#include "cli/fe_export.hpp"
#include "cli/program_lookup.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/export/fmu_export.hpp"
#include "runtime/io/output.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

namespace rheo::cli {
namespace {

struct Options {
  std::string file;
  std::string model;
  FeExportOptions fe;
  std::string fmu;
  int fmi = 2;
};

// DataError unless a file can be created beside PATH (the write's temporary file): a missing or
// read-only folder, found before any work. Probes with a file of its own, removed at once.
void check_folder_takes_files(const std::string& path) {
  runtime::check_output_destination(path);
  if (path == "-") return;
  const std::filesystem::path folder = std::filesystem::path(path).parent_path().empty() ? "." : std::filesystem::path(path).parent_path();
  const std::string probe = (folder / fmt::format(".rheo-export-probe-{}", ::getpid())).string();
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0)
    throw runtime::DataError(
        fmt::format("{}: error: cannot create a file in {} ({}); choose a folder you can write to", path, folder.string(), std::strerror(errno)));
  ::close(fd);
  ::unlink(probe.c_str());
}

// The FMU of the chosen model, written atomically to o.fmu (its folder checked before any work by
// the caller): a failed export leaves no file there.
int export_fmu(const Options& o) {
  const std::string text = lang::read_source(o.file);
  const lang::Program program = lang::compile_source(o.file, text);
  const lang::CheckedModel& model = chosen_model(program, o.file, o.model, "to export", "choose one with --model");
  const std::string name = std::filesystem::path(o.file).filename().string();
  const std::string fmu = runtime::exporter::fmu_archive(model, {name, text, RHEO_VERSION});
  runtime::write_output(o.fmu, fmu);
  if (o.fmu != "-")
    std::cerr << fmt::format("rheo: FMU of model {} (FMI 2.0 co-simulation, {} parameters) written to {}\n", model.name, model.parameters.size(),
                             o.fmu);
  return runtime::exit_code::ok;
}

}  // namespace

Command add_export_command(CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("file", o->file, "The .rheo file")->required();
  app.add_option("--model", o->model, "The model to export (default: the file's only model)");
  app.add_option("--fmu", o->fmu,
                 "Write the model as a Functional Mock-up Unit for co-simulation here (OUT.fmu): input u [mm], output F [N], "
                 "the parameters settable until initialisation ends");
  app.add_option("--fmi", o->fmi, "The FMI version of the FMU: 2 (default); 3 is not available yet")->check(CLI::IsMember({2, 3}));
  add_fe_export_options(app, o->fe);
  app.footer(
      "The FMU steps the network with the fixed-step kernels of `rheo simulate --solver fixed`. The Abaqus and ANSYS cards take a "
      "model whose branches are springs, maxwell elements (or a spring and a dashpot in series) and springpots acting side by "
      "side; any other branch is refused at its line:col, or left out by name with --leave-out. Destinations are checked before "
      "anything is computed. See docs/cli.md#rheo-export.");
  return [o] {
    if (o->fmu.empty() && !o->fe.any()) throw runtime::UsageError("nothing to export; give --fmu OUT.fmu, --abaqus OUT.inp and/or --ansys OUT.mac");
    if (!o->fmu.empty()) {
      if (o->fmi == 3)
        throw runtime::UsageError(
            fmt::format("--fmi 3: FMI 3.0 export is not available yet in rheo {}; export FMI 2.0 co-simulation (--fmi 2, the default), which the "
                        "FMI 3.0 hosts import as well",
                        RHEO_VERSION));
      check_folder_takes_files(o->fmu);
    }
    if (o->fe.any()) {
      check_fe_export_options(o->fe);
      const lang::Program program = lang::load_program(o->file);
      const lang::CheckedModel& model = chosen_model(program, o->file, o->model, "to export", "choose one with --model");
      const int status = run_fe_export(o->file, program, model, o->fe);
      if (status != runtime::exit_code::ok || o->fmu.empty()) return status;
    }
    return export_fmu(*o);
  };
}

}  // namespace rheo::cli
