// Runs tests/corpus: valid/*.rheo must compile cleanly; invalid/*.rheo must report exactly the
// errors listed in their `# expect error LINE:COL: MESSAGE-SUBSTRING` comments. Hostile cases too
// large or binary to keep as files (deep nesting, bytes that are not UTF-8 text) are generated.
#include "lang/frontend.hpp"
#include "lang/limits.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace corpus_test {

namespace fs = std::filesystem;
using namespace rheo::lang;
using namespace std::string_literals;

namespace {

std::vector<fs::path> corpus(const std::string& sub) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(fs::path(RHEO_CORPUS_DIR) / sub))
    if (e.path().extension() == ".rheo") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

struct Expectation {
  int line, column;
  std::string substring;
};

std::vector<Expectation> expectations(const fs::path& file) {
  std::ifstream in(file);
  std::vector<Expectation> out;
  static const std::regex pattern(R"(#\s*expect error (\d+):(\d+): (.*\S))");
  std::string line;
  std::smatch m;
  while (std::getline(in, line))
    if (std::regex_search(line, m, pattern)) out.push_back({std::stoi(m[1]), std::stoi(m[2]), m[3]});
  return out;
}

// Checks that FILE reports exactly the EXPECTED errors.
void check_reports(const fs::path& file, const std::vector<Expectation>& expected) {
  std::vector<Diagnostic> reported;
  std::string text;
  try {
    load_program(file.string());
  } catch (const CompileError& e) {
    reported = e.diagnostics();
    text = e.what();
  }
  CAPTURE(text);
  std::vector<bool> used(reported.size(), false);
  for (const auto& x : expected) {
    bool found = false;
    for (std::size_t i = 0; i < reported.size() && !found; ++i) {
      const auto& d = reported[i];
      if (!used[i] && d.where.file == file.string() && d.where.line == x.line && d.where.column == x.column &&
          d.message.find(x.substring) != std::string::npos)
        used[i] = found = true;
    }
    CHECK_MESSAGE(found, "expected error ", x.line, ":", x.column, ": ", x.substring);
  }
  for (std::size_t i = 0; i < reported.size(); ++i)
    CHECK_MESSAGE(used[i], "unexpected error ", reported[i].where.line, ":", reported[i].where.column, ": ", reported[i].message);
}

std::string repeat(std::string_view text, int times) {
  std::string out;
  for (int i = 0; i < times; ++i) out += text;
  return out;
}

struct Generated {
  std::string name, text;
  Expectation expected;
};

// Hostile inputs, each with the one error it must report (the nesting ones one level past the
// limit, at the rule that would go deeper).
std::vector<Generated> generated_corpus() {
  const int blocks = rheo::lang::max_block_depth + 1;
  const int levels = rheo::lang::max_expression_depth;
  const std::string too_deep = fmt::format("nested deeper than {} levels", levels);
  std::vector<Generated> out;
  // Blocks one per line: the first past the limit is on line blocks + 1 (line 1 opens the model).
  out.push_back({"series_nesting",
                 "model m {\n" + repeat("series {\n", blocks) + "spring s (k = 1 N/mm) spring t (k = 1 N/mm)\n" + repeat("}\n", blocks) + "}\n",
                 {blocks + 1, 1, fmt::format("blocks nested deeper than {} levels", rheo::lang::max_block_depth)}});
  out.push_back({"parallel_nesting",
                 "model m {\n" + repeat("parallel {\n", blocks) + "spring s (k = 1 N/mm)\n" + repeat("}\n", blocks) + "}\n",
                 {blocks + 1, 1, "blocks nested deeper than"}});
  std::string alternating = "model m {\n";
  for (int i = 0; i < blocks; ++i) alternating += fmt::format("{} {{ spring a{} (k = 1 N/mm)\n", i % 2 ? "series" : "parallel", i);
  out.push_back({"alternating_nesting", alternating + repeat("}\n", blocks + 1), {blocks + 1, 1, "blocks nested deeper than"}});
  // "  spring s (k = " is 16 columns: the LEVELS-th '(' or '-' would open level LEVELS + 1.
  out.push_back(
      {"parentheses", "model m {\n  spring s (k = " + repeat("(", levels) + "1" + repeat(")", levels) + " N/mm)\n}\n", {2, 16 + levels, too_deep}});
  out.push_back({"unary_minus", "model m {\n  spring s (k = " + repeat("-", levels) + "1 N/mm)\n}\n", {2, 16 + levels, too_deep}});
  // A chain of N operators nests N + 1 levels: the LEVELS-th '+' stands at column 4 * LEVELS + 15.
  out.push_back({"operator_chain", "model m {\n  spring s (k = 1" + repeat(" + 1", levels) + " N/mm)\n}\n", {2, 4 * levels + 15, too_deep}});
  out.push_back({"byte_ff", "model m {\n  spring s (k = 1 N/mm)\n  # caf\xff\n}\n", {3, 8, "found byte 0xFF, which is not UTF-8"}});
  out.push_back({"latin1_string",
                 "model m { spring s (k = 1 N/mm) }\nsimulate {\n  history file = \"r\xe9sum\xe9.csv\"\n}\n",
                 {3, 20, "found byte 0xE9, which is not UTF-8"}});
  out.push_back({"truncated_sequence", "model m { spring s (k = 1 N/mm) } # \xe2\x82", {1, 37, "found byte 0xE2"}});
  out.push_back({"overlong_slash", "# \xc0\xaf\nmodel m { spring s (k = 1 N/mm) }\n", {1, 3, "found byte 0xC0"}});
  out.push_back({"surrogate", "model m { spring s (k = 1 N/mm) }\n# \xed\xa0\x80\n", {2, 3, "found byte 0xED"}});
  out.push_back({"nul", "model m {\n  spring s (k = 1 N/mm)\0\n}\n"s, {2, 24, "found a NUL byte"}});
  return out;
}

}  // namespace

TEST_CASE("corpus: valid files compile cleanly") {
  auto files = corpus("valid");
  REQUIRE(files.size() >= 5);
  for (const auto& f : files) {
    CAPTURE(f.string());
    try {
      Program p = load_program(f.string());
      CHECK(!p.models.empty());
    } catch (const CompileError& e) {
      FAIL_CHECK(std::string(e.what()));
    }
  }
}

TEST_CASE("corpus: invalid files report exactly the expected errors") {
  auto files = corpus("invalid");
  REQUIRE(files.size() >= 20);
  for (const auto& f : files) {
    CAPTURE(f.string());
    auto expected = expectations(f);
    REQUIRE_MESSAGE(!expected.empty(), "no `# expect error` line in ", f.string());
    check_reports(f, expected);
  }
}

TEST_CASE("corpus: generated hostile files report the expected error at the rule that fails") {
  const fs::path dir = fs::temp_directory_path() / fmt::format("rheo-corpus-{}", ::getpid());
  fs::create_directories(dir);
  for (const auto& g : generated_corpus()) {
    CAPTURE(g.name);
    const fs::path file = dir / (g.name + ".rheo");
    std::ofstream(file, std::ios::binary) << g.text;
    check_reports(file, {g.expected});
  }
  fs::remove_all(dir);
}

}  // namespace corpus_test
