// Runs tests/corpus: valid/*.rheo must compile cleanly; invalid/*.rheo must report exactly the
// errors listed in their `# expect error LINE:COL: MESSAGE-SUBSTRING` comments.
#include "lang/frontend.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace fs = std::filesystem;
using namespace rheo::lang;

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
    std::vector<Diagnostic> reported;
    std::string text;
    try {
      load_program(f.string());
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
        if (!used[i] && d.where.file == f.string() && d.where.line == x.line && d.where.column == x.column &&
            d.message.find(x.substring) != std::string::npos)
          used[i] = found = true;
      }
      CHECK_MESSAGE(found, "expected error ", x.line, ":", x.column, ": ", x.substring);
    }
    for (std::size_t i = 0; i < reported.size(); ++i)
      CHECK_MESSAGE(used[i], "unexpected error ", reported[i].where.line, ":", reported[i].where.column, ": ", reported[i].message);
  }
}
