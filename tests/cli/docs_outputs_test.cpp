// The files the commands of docs/tutorial.md and README.md write (-o, --output, --report,
// --plot, --abaqus, --ansys), and those the examples' `output` lines name, are ignored by git: following the
// tutorial leaves `git status` clean. The commands write into examples/, not the repository
// root. Needs git and a checkout; skipped without them.
#include "cli_support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace docs_outputs_test {

namespace fs = std::filesystem;

namespace {

// The files `$ build/rheo ...` lines of TEXT write, relative to the repository root.
std::vector<std::string> written_by_commands(const std::string& text) {
  static const std::regex command(R"((?:^|\n)\$ build/rheo ([^\n]*))");
  static const std::regex destination(R"((?:-o|--output|--report|--plot|--abaqus|--ansys|--fmu) ([^\s'`|]+))");
  std::vector<std::string> out;
  for (auto c = std::sregex_iterator(text.begin(), text.end(), command); c != std::sregex_iterator(); ++c) {
    const std::string line = (*c)[1];
    for (auto d = std::sregex_iterator(line.begin(), line.end(), destination); d != std::sregex_iterator(); ++d)
      if ((*d)[1] != "-") out.push_back((*d)[1]);
  }
  return out;
}

bool ignored(const std::string& path) {
  return std::system(fmt::format("git -C '{}' check-ignore -q --no-index '{}'", RHEO_SOURCE_DIR, path).c_str()) == 0;
}

}  // namespace

TEST_CASE("every file the tutorial's commands and the examples' output lines write lies in examples/ and is ignored by git") {
  if (std::system(fmt::format("git -C '{}' rev-parse --is-inside-work-tree >/dev/null 2>&1", RHEO_SOURCE_DIR).c_str()) != 0) {
    MESSAGE("SKIPPED: the source tree is no git checkout");
    return;
  }
  std::vector<std::string> outputs;
  for (const char* doc : {"docs/tutorial.md", "README.md"})
    for (auto& path : written_by_commands(rheo::test::read_required(fs::path(RHEO_SOURCE_DIR) / doc))) outputs.push_back(std::move(path));
  CHECK(outputs.size() >= 10);
  for (const auto& path : outputs) {
    CAPTURE(path);
    CHECK(path.rfind("examples/", 0) == 0);  // not the repository root
  }
  static const std::regex output_line(R"(\boutput "([^"]+)\")");
  for (const auto& entry : fs::directory_iterator(RHEO_EXAMPLES_DIR))
    if (entry.path().extension() == ".rheo") {
      const std::string text = rheo::test::read_required(entry.path());
      for (auto m = std::sregex_iterator(text.begin(), text.end(), output_line); m != std::sregex_iterator(); ++m)
        outputs.push_back("examples/" + std::string((*m)[1]));
    }
  for (const auto& path : outputs) {
    CAPTURE(path);
    CHECK(ignored(path));
  }
  CHECK_FALSE(ignored("examples/bushing_d.rheo"));  // the sources are not
  CHECK_FALSE(ignored("docs/tutorial.md"));
}

}  // namespace docs_outputs_test
