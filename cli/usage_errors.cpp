#include "cli/usage_errors.hpp"

#include "lang/names.hpp"
#include "lang/text_encoding.hpp"

#include <fmt/format.h>

#include <cctype>
#include <optional>
#include <string_view>

namespace rheo::cli {
namespace {

// True for an argument that is an option's name ("--protocol", "--seed=2", "-o"), not a value
// ("-" for standard output, "-1", "-.5").
bool names_an_option(const std::string& argument) {
  if (argument.size() < 2 || argument[0] != '-') return false;
  const char second = argument[1];
  return !(std::isdigit(static_cast<unsigned char>(second)) || second == '.');
}

// "--seed=2" -> "--seed"; "-o" stays "-o".
std::string option_name(const std::string& argument) { return argument.substr(0, argument.find('=')); }

// Every spelling of APP's options: "--protocol", "-o", "--output", "--help".
std::vector<std::string> option_spellings(const CLI::App& app) {
  std::vector<std::string> out;
  for (const CLI::Option* option : app.get_options()) {
    for (const std::string& name : option->get_lnames()) out.push_back("--" + name);
    for (const std::string& name : option->get_snames()) out.push_back("-" + name);
  }
  return out;
}

std::vector<std::string> command_names(const CLI::App& app) {
  std::vector<std::string> out;
  for (const CLI::App* sub : app.get_subcommands({})) out.push_back(sub->get_name());
  return out;
}

// The first option among ARGUMENTS[FROM, TO) that APP does not know, as a message; nullopt when
// it knows them all. Arguments after "--" are values.
std::optional<std::string> unknown_option(const CLI::App& app, const std::string& command, const std::vector<std::string>& arguments,
                                          std::size_t from, std::size_t to) {
  for (std::size_t k = from; k < to; ++k) {
    if (arguments[k] == "--") return std::nullopt;
    if (!names_an_option(arguments[k])) continue;
    const std::string name = option_name(arguments[k]);
    if (app.get_option_no_throw(name) != nullptr) continue;
    return fmt::format("unknown option '{}' for {};{} see '{} --help' for its options", lang::printable(name), command,
                       lang::did_you_mean(name, option_spellings(app)), command);
  }
  return std::nullopt;
}

}  // namespace

std::string usage_message(const CLI::App& app, const CLI::ParseError& error, const std::vector<std::string>& arguments) {
  const std::vector<std::string> commands = command_names(app);
  // The command: the first argument that is no option.
  std::size_t at = 0;
  while (at < arguments.size() && names_an_option(arguments[at])) ++at;
  if (auto unknown = unknown_option(app, "rheo", arguments, 0, at)) return *unknown;
  if (at == arguments.size())
    return fmt::format("no command given; name one: rheo COMMAND FILE ..., where COMMAND is one of {} (see 'rheo --help')", lang::join(commands));
  const std::string& word = arguments[at];
  const CLI::App* sub = nullptr;
  for (const CLI::App* candidate : app.get_subcommands({}))
    if (candidate->get_name() == word) sub = candidate;
  if (sub == nullptr)
    return fmt::format("unknown command '{}';{} the commands are {} (see 'rheo --help')", lang::printable(word), lang::did_you_mean(word, commands),
                       lang::join(commands));
  const std::string command = "rheo " + sub->get_name();
  if (auto unknown = unknown_option(*sub, command, arguments, at + 1, arguments.size())) return *unknown;
  std::string what = error.what();
  for (const std::string_view prefix : {"The following argument was not expected: ", "The following arguments were not expected: "})
    if (what.starts_with(prefix)) what = fmt::format("unexpected argument '{}'", what.substr(prefix.size()));  // CLI::ExtrasError
  return fmt::format("{}: {}; see '{} --help'", command, lang::printable(what, 300), command);
}

}  // namespace rheo::cli
