// `rheo export FILE --fmu OUT.fmu [--model NAME] [--fmi 2|3]`: a model as a Functional Mock-up
// Unit for co-simulation (runtime/export/fmu_export.hpp, docs/cli.md#rheo-export).
#include "lang/frontend.hpp"
#include "cli/commands.hpp"
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

namespace rheo::cli {
namespace {

struct Options {
  std::string file;
  std::string fmu;
  std::string model;
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

// The FMU of the chosen model, written atomically to o.fmu: a destination that cannot be written
// is found before any work, and a failed export leaves no file there.
int export_fmu(const Options& o) {
  if (o.fmi == 3)
    throw runtime::UsageError(
        fmt::format("--fmi 3: FMI 3.0 export is not available yet in rheo {}; export FMI 2.0 co-simulation (--fmi 2, the default), which the "
                    "FMI 3.0 hosts import as well",
                    RHEO_VERSION));
  check_folder_takes_files(o.fmu);
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
  app.add_option("--fmu", o->fmu,
                 "Write the model as a Functional Mock-up Unit for co-simulation here (OUT.fmu): input u [mm], output F [N], "
                 "the parameters settable until initialisation ends");
  app.add_option("--model", o->model, "The model to export (needed when the file defines several)");
  app.add_option("--fmi", o->fmi, "The FMI version of the FMU: 2 (default); 3 is not available yet")->check(CLI::IsMember({2, 3}));
  app.footer("The FMU steps the network with the fixed-step kernels of `rheo simulate --solver fixed`; see docs/cli.md#rheo-export.");
  return [o] {
    if (o->fmu.empty()) throw runtime::UsageError("rheo export: name what to write, e.g. --fmu OUT.fmu");
    return export_fmu(*o);
  };
}

}  // namespace rheo::cli
