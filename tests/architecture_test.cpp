// The rooms of the source tree and their order (docs/architecture.md): a file may include its
// own room and the rooms below it, never one above or beside it. The CMake targets link in the
// same order; this test reads every #include of the tree so that a header-only arrow the
// linker cannot see is caught too.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// Rank of each room; a room may include rooms of lower rank. Rooms of equal rank are siblings
// and may not include each other.
const std::map<std::string, int>& ranks() {
  static const std::map<std::string, int> r{
      {"stdlib", 0},
      {"lang", 1},
      {"runtime/core", 2},
      {"runtime/network", 3},
      {"runtime/stepping", 4},
      {"runtime/closed_form", 4},
      {"runtime/dae", 4},
      {"runtime/io", 4},
      {"runtime/protocols", 5},
      {"runtime/fmu", 5},
      {"runtime/fit", 6},
      {"runtime/export", 6},
      {"runtime/report", 7},
      {"runtime/diagnosis", 8},
      {"cli", 9},
  };
  return r;
}

// The room of a path relative to the project ("runtime/fit/fit.cpp" -> "runtime/fit").
std::optional<std::string> room_of(const std::string& path) {
  for (const auto& [room, rank] : ranks())
    if (path.starts_with(room + "/")) return room;
  return std::nullopt;
}

struct Include {
  std::string file, target;
  int line;
};

std::vector<Include> project_includes() {
  std::vector<Include> out;
  const std::regex include(R"re(^\s*#\s*include\s*"([^"]+)")re");
  for (const char* top : {"lang", "runtime", "cli", "stdlib"}) {
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(RHEO_SOURCE_DIR) / top)) {
      const auto ext = entry.path().extension();
      if (ext != ".cpp" && ext != ".hpp") continue;
      const std::string file = fs::relative(entry.path(), RHEO_SOURCE_DIR).generic_string();
      std::ifstream in(entry.path());
      std::string text;
      int line = 0;
      std::smatch m;
      while (std::getline(in, text)) {
        ++line;
        if (std::regex_search(text, m, include)) out.push_back({file, m[1].str(), line});
      }
    }
  }
  return out;
}

}  // namespace

TEST_CASE("architecture: every #include goes to the file's own room or a room below it") {
  const auto includes = project_includes();
  REQUIRE(includes.size() > 300);  // the scan found the tree
  int checked = 0;
  for (const Include& inc : includes) {
    const auto from = room_of(inc.file), to = room_of(inc.target);
    if (!to) continue;  // a file of the same folder by bare name, or a generated one
    REQUIRE_MESSAGE(from.has_value(), inc.file << " lies in no room of docs/architecture.md; add it there and here");
    ++checked;
    if (*from == *to) continue;
    CHECK_MESSAGE(ranks().at(*to) < ranks().at(*from),
                  fmt::format("{}:{} includes {}: room {} may not depend on {} (docs/architecture.md)", inc.file, inc.line, inc.target, *from, *to));
  }
  CHECK(checked > 300);
}

TEST_CASE("architecture: the check catches an arrow that runs up or sideways") {
  CHECK(ranks().at("runtime/core") < ranks().at("runtime/network"));
  CHECK(room_of("runtime/fit/fit.cpp") == "runtime/fit");
  CHECK(room_of("cli/main.cpp") == "cli");
  CHECK_FALSE(room_of("tests/support.hpp").has_value());
  // Siblings: neither may include the other.
  CHECK_FALSE(ranks().at("runtime/dae") < ranks().at("runtime/stepping"));
  CHECK_FALSE(ranks().at("runtime/stepping") < ranks().at("runtime/dae"));
}
