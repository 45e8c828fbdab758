// docs/language.md against the schemas it documents: every element kind and each of its
// parameters, every protocol and each of its settings, every fit-block setting and every
// standard-library model has its entry, so a new key or element cannot ship undocumented.
#include "lang/element_schema.hpp"
#include "lang/fit_schema.hpp"
#include "lang/protocol_schema.hpp"
#include "lang/stdlib.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

namespace docs_language_test {

using namespace rheo::lang;

namespace {

const std::string& language_md() {
  static const std::string text = [] {
    std::ifstream in(std::string(RHEO_SOURCE_DIR) + "/docs/language.md");
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }();
  return text;
}

// The text of the section headed `## TITLE`, up to the next `## `.
std::string section(const std::string& title) {
  const std::string& text = language_md();
  const auto start = text.find("\n## " + title + "\n");
  REQUIRE_MESSAGE(start != std::string::npos, "docs/language.md has no section ", title);
  const auto end = text.find("\n## ", start + 1);
  return text.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

// The table row of SECTION whose first cell names `NAME` (alone or in a list: "`a`, `b`"), or "".
std::string row(const std::string& section, const std::string& name) {
  std::istringstream lines(section);
  for (std::string line; std::getline(lines, line);) {
    if (!line.starts_with("| `")) continue;
    const std::string first_cell = line.substr(0, line.find(" |", 2));
    if (first_cell.find(fmt::format("`{}`", name)) != std::string::npos) return line;
  }
  return "";
}

// TEXT names KEY in code: `key` or `key = value`.
bool mentions(const std::string& text, std::string_view key) {
  return text.find(fmt::format("`{}`", key)) != std::string::npos || text.find(fmt::format("`{} ", key)) != std::string::npos;
}

}  // namespace

TEST_CASE("docs/language.md: every element kind has a row naming each of its parameters") {
  const std::string elements = section("Elements");
  for (const ElementSpec& spec : element_specs()) {
    CAPTURE(spec.kind);
    const std::string line = row(elements, std::string(spec.kind));
    REQUIRE_MESSAGE(!line.empty(), "no row for the element");
    for (const auto& slots : {spec.slots, spec.alternative, spec.split})
      for (const ParameterSpec& p : slots) {
        CAPTURE(p.name);
        CHECK(mentions(line, p.name));
      }
  }
}

TEST_CASE("docs/language.md: every protocol has a row naming each of its settings (or the paragraph on the common ones)") {
  const std::string simulate = section("The simulate block");
  const auto common = simulate.find("Every protocol also takes");
  REQUIRE(common != std::string::npos);
  const std::string common_paragraph = simulate.substr(common, simulate.find("\n\n", common) - common);
  for (const std::string& name : protocol_names()) {
    CAPTURE(name);
    const std::string line = row(simulate, name);
    REQUIRE_MESSAGE(!line.empty(), "no row for the protocol");
    for (const std::string& key : protocol_setting_keys(*protocol_kind(name))) {
      CAPTURE(key);
      CHECK((mentions(line, key) || mentions(common_paragraph, key)));
    }
  }
}

TEST_CASE("docs/language.md: every fit-block setting has a row") {
  const std::string fit = section("The fit block");
  for (const std::string& key : fit_setting_keys()) {
    CAPTURE(key);
    CHECK(!row(fit, key).empty());
  }
}

TEST_CASE("docs/language.md: every standard-library model has a row") {
  const std::string stdlib = section("Standard library");
  for (const std::string& name : stdlib_names()) {
    CAPTURE(name);
    CHECK(!row(stdlib, name).empty());
  }
}

}  // namespace docs_language_test
