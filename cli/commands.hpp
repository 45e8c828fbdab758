// Subcommands of the rheo CLI. Each registers its options on the CLI11 app and returns the
// function that runs it; exit codes are those of runtime/core/errors.hpp (docs/cli.md).
#pragma once

#include <CLI/CLI.hpp>

#include <functional>

namespace rheo::cli {

using Command = std::function<int()>;

Command add_check_command(CLI::App& app);
Command add_simulate_command(CLI::App& app);
Command add_fit_command(CLI::App& app);
Command add_report_command(CLI::App& app);
Command add_diagnose_command(CLI::App& app);
Command add_refine_command(CLI::App& app);
Command add_export_command(CLI::App& app);

}  // namespace rheo::cli
