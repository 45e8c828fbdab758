// docs/cli.md against the binary: every command `rheo --help` lists has a synopsis line in the
// first code block of docs/cli.md, and every option `rheo COMMAND --help` prints appears in that
// command's synopsis (its long or its short name) and, as `--name`, in the text. A new option
// or command therefore fails here until it is documented.
#include "cli_support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace docs_cli_test {

namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The entries of a CLI11 help section ("Subcommands:", "Options:"): lines indented by exactly two
// spaces; descriptions that wrap are indented further and are skipped.
std::vector<std::string> section_entries(const std::string& help, const std::string& section) {
  std::vector<std::string> entries;
  bool inside = false;
  for (const auto& line : lines_of(help)) {
    if (line == section) {
      inside = true;
    } else if (inside && line.empty()) {
      break;
    } else if (inside && line.size() > 2 && line.compare(0, 2, "  ") == 0 && line[2] != ' ') {
      entries.push_back(line.substr(2, line.find(' ', 2) - 2));
    }
  }
  return entries;
}

// "check" -> the synopsis of `rheo check` in docs/cli.md's first code block, continuation lines
// (indented) included.
std::string synopsis(const std::string& doc, const std::string& command) {
  const auto lines = lines_of(doc);
  std::string out;
  bool in_block = false, in_command = false;
  for (const auto& line : lines) {
    if (line.rfind("```", 0) == 0) {
      if (in_block) break;
      in_block = true;
      continue;
    }
    if (!in_block) continue;
    if (line.rfind("rheo ", 0) == 0) {
      in_command = line.rfind("rheo " + command + " ", 0) == 0;
    } else if (!(line.rfind(" ", 0) == 0)) {
      in_command = false;
    }
    if (in_command) out += line + "\n";
  }
  return out;
}

bool has_word(const std::string& text, const std::string& option) {
  // The option as a whole word: not followed by a letter, digit or '-'.
  // Options hold only letters, digits, '-' and '`', none of them special in a regex.
  const std::regex pattern(option + R"((?![A-Za-z0-9-]))");
  return std::regex_search(text, pattern);
}

std::vector<std::string> commands() {
  const auto run = rheo::test::run_rheo("--help");
  REQUIRE(run.code == 0);
  return section_entries(run.out, "Subcommands:");
}

}  // namespace

TEST_CASE("docs/cli.md: the parsing helpers read CLI11 help and the synopsis") {
  const std::string help =
      "Options:\n  -h,--help                   Print\n  --solver TEXT:{a,b}\n"
      "                              wrapped -description\n  -o,--output TEXT  Write\n\nFooter\n";
  CHECK(section_entries(help, "Options:") == std::vector<std::string>{"-h,--help", "--solver", "-o,--output"});
  const std::string doc = "# x\n\n```\nrheo a FILE [--b]\n       [--c N]\nrheo ab FILE [--d]\n```\n";
  CHECK(synopsis(doc, "a") == "rheo a FILE [--b]\n       [--c N]\n");
  CHECK(has_word("[--seed S]", "--seed"));
  CHECK_FALSE(has_word("[--seeds S]", "--seed"));
  CHECK_FALSE(has_word("[--seed-x S]", "--seed"));
}

TEST_CASE("docs/cli.md has a synopsis for every command of rheo --help") {
  const std::string doc = rheo::test::read_required(std::string(RHEO_SOURCE_DIR) + "/docs/cli.md");
  const auto names = commands();
  REQUIRE(names.size() >= 4);
  for (const auto& command : names) {
    CAPTURE(command);
    CHECK_FALSE(synopsis(doc, command).empty());
  }
}

TEST_CASE("docs/cli.md documents every option of every command's --help") {
  const std::string doc = rheo::test::read_required(std::string(RHEO_SOURCE_DIR) + "/docs/cli.md");
  for (const auto& command : commands()) {
    const auto run = rheo::test::run_rheo(command + " --help");
    REQUIRE(run.code == 0);
    const auto options = section_entries(run.out, "Options:");
    REQUIRE_FALSE(options.empty());
    const std::string line = synopsis(doc, command);
    for (const auto& entry : options) {
      if (entry == "-h,--help") continue;  // `rheo COMMAND --help` is in the synopsis once for all
      std::vector<std::string> names;
      std::stringstream parts(entry);
      for (std::string name; std::getline(parts, name, ',');) names.push_back(name);
      const std::string& long_name = names.back();
      CAPTURE(command);
      CAPTURE(entry);
      bool in_synopsis = false;
      for (const auto& name : names) in_synopsis = in_synopsis || has_word(line, name);
      CHECK(in_synopsis);
      CHECK(has_word(doc, "`" + long_name));
    }
  }
}

}  // namespace docs_cli_test
