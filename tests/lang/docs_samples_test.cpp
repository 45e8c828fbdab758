// Every sample of the language in the documentation parses (#22 item 1): the fenced blocks of
// README.md and docs/*.md that are rheo source (their first statement a model, import,
// simulate or fit block), with a line `...` taken as an elision, and the element statements
// that docs/language.md shows inline (`series { ... }`, `parallel { ... }`), inside a model.
// docs/errors.md is left out: its samples are wrong on purpose.
#include "lang/errors.hpp"
#include "lang/parser.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace docs_samples_test {

using namespace rheo::lang;

namespace {

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::vector<std::filesystem::path> documents() {
  const std::filesystem::path root(RHEO_SOURCE_DIR);
  std::vector<std::filesystem::path> out{root / "README.md"};
  for (const auto& entry : std::filesystem::directory_iterator(root / "docs"))
    if (entry.path().extension() == ".md" && entry.path().filename() != "errors.md") out.push_back(entry.path());
  std::sort(out.begin(), out.end());
  return out;
}

// The fenced code blocks of TEXT.
std::vector<std::string> fenced_blocks(const std::string& text) {
  std::vector<std::string> blocks;
  for (std::size_t open = text.find("```"); open != std::string::npos;) {
    const std::size_t body = text.find('\n', open);
    const std::size_t close = text.find("\n```", body);
    if (body == std::string::npos || close == std::string::npos) break;
    blocks.push_back(text.substr(body + 1, close + 1 - (body + 1)));
    open = text.find("```", close + 4);
  }
  return blocks;
}

// Whether BLOCK is rheo source: its first line that is not blank or a comment opens a model,
// simulate or fit block, or imports a model.
bool is_rheo_source(const std::string& block) {
  static const std::regex first_statement(R"(^(model\s+\w+\s*\{|import\s+\w|simulate\s*\{|fit(\s+\w+)?\s*\{))");
  std::istringstream lines(block);
  for (std::string line; std::getline(lines, line);) {
    const auto start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] == '#') continue;
    return std::regex_search(line.substr(start), first_statement);
  }
  return false;
}

std::string without_elisions(const std::string& block) {
  std::istringstream lines(block);
  std::string out;
  for (std::string line; std::getline(lines, line);)
    if (line.find_first_not_of(" \t") == std::string::npos || line.substr(line.find_first_not_of(" \t")) != "...") out += line + "\n";
  return out;
}

std::string parse_error(const std::string& name, const std::string& text) {
  try {
    parse(name, text);
  } catch (const CompileError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("docs: every rheo sample in a fenced block parses") {
  int samples = 0;
  for (const auto& path : documents()) {
    int index = 0;
    for (const std::string& block : fenced_blocks(read(path))) {
      ++index;
      if (!is_rheo_source(block)) continue;
      ++samples;
      CAPTURE(path.filename().string());
      CAPTURE(index);
      CAPTURE(block);
      CHECK(parse_error(path.filename().string(), without_elisions(block)) == "");
    }
  }
  CHECK(samples >= 8);  // the README's and the tutorial's models are among them
}

TEST_CASE("docs: the inline series and parallel statements of language.md parse inside a model") {
  const std::string text = read(std::filesystem::path(RHEO_SOURCE_DIR) / "docs" / "language.md");
  static const std::regex inline_statement(R"(`((series|parallel)( \w+)? \{[^`]*\})`)");
  int statements = 0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), inline_statement); it != std::sregex_iterator(); ++it) {
    const std::string statement = (*it)[1].str();
    if (statement.find("...") != std::string::npos) continue;  // a schematic, not a statement
    ++statements;
    CAPTURE(statement);
    CHECK(parse_error("language.md", "model m {\n  " + statement + "\n}\n") == "");
  }
  CHECK(statements >= 1);  // the gap row's example at least
}

}  // namespace docs_samples_test
