// Command-line mistakes in rheo's words (docs/errors.md#usage-errors). CLI11 finds them; this
// says what was wrong and what to give instead, naming the nearest command or option to a
// misspelt one ("did you mean 'simulate'?"). The caller prints "rheo: error: " before it and
// exits with the usage code, 2.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace rheo::cli {

// The message for ERROR, which CLI11 raised parsing ARGUMENTS (argv without the program name)
// for APP, the rheo command line with its subcommands. Not for CLI::Success, CallForHelp or
// CallForVersion, which are no errors. One line, no "rheo: error: " and no newline.
std::string usage_message(const CLI::App& app, const CLI::ParseError& error, const std::vector<std::string>& arguments);

}  // namespace rheo::cli
