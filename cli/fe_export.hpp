// `rheo export --abaqus/--ansys`: a model's linear viscoelastic part as finite-element material
// cards (runtime/export/). The options, the geometry they or the fit block give, and the run.
#pragma once

#include "lang/model.hpp"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace rheo::cli {

struct FeExportOptions {
  std::string abaqus;  // OUT.inp, or empty
  std::string ansys;   // OUT.mac, or empty
  std::string area;    // "314 mm^2" as given, or empty
  std::string height;  // "10 mm" as given, or empty
  bool no_geometry = false;
  std::string modulus = "young";
  double poisson = 0.49;
  std::vector<std::string> leave_out;

  bool any() const { return !abaqus.empty() || !ansys.empty(); }
};

void add_fe_export_options(CLI::App& app, FeExportOptions& o);

// UsageError for options that do not go together (--area without --height, --no-geometry with
// them); DataError for a destination that cannot be written. Called before any work.
void check_fe_export_options(const FeExportOptions& o);

// Writes the cards of MODEL (from PROGRAM, loaded from FILE) to every destination o names, all or
// none: every text is made before the first is written. Reports on standard error; returns the
// exit code.
int run_fe_export(const std::string& file, const lang::Program& program, const lang::CheckedModel& model, const FeExportOptions& o);

}  // namespace rheo::cli
