// The files a .rheo text names and their relocation (lang/file_references.hpp): every kind of
// reference found, relative names rewritten to name the same file from the new folder,
// absolute names and all other bytes kept.
#include "lang/file_references.hpp"

#include <doctest/doctest.h>

#include <string>

namespace file_references_test {

using namespace rheo::lang;

namespace {

const std::string kSource =
    "# data \"comment.csv\" is not a reference\n"
    "model m { spring k (k = 1 N/mm in [0.1, 10]) }\n"
    "simulate m {\n"
    "  history file = \"rig/run 1.csv\"\n"
    "  output \"out/h.csv\"\n"
    "}\n"
    "fit m {\n"
    "  data \"data/h.csv\", weight = 2\n"
    "  data \"/abs/h.csv\"\n"
    "  output \"fitted.rheo\"\n"
    "}\n";

}  // namespace

TEST_CASE("file references: history files, outputs and data lines, in text order") {
  const auto refs = file_references("a.rheo", kSource);
  REQUIRE(refs.size() == 5);
  const char* names[] = {"rig/run 1.csv", "out/h.csv", "data/h.csv", "/abs/h.csv", "fitted.rheo"};
  for (std::size_t i = 0; i < refs.size(); ++i) {
    CAPTURE(i);
    CHECK(refs[i].name == names[i]);
    CHECK(kSource.substr(static_cast<std::size_t>(refs[i].begin), static_cast<std::size_t>(refs[i].end - refs[i].begin)) == names[i]);
    CHECK(kSource[static_cast<std::size_t>(refs[i].begin - 1)] == '"');
  }
}

TEST_CASE("relocated source: relative names rewritten from the new folder, the rest byte for byte") {
  const std::string moved = relocated_source(kSource, "/p/q/a.rheo", "/p/r/s/b.rheo");
  std::string expected = kSource;
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"\"rig/run 1.csv\"", "\"../../q/rig/run 1.csv\""},
                                 {"\"out/h.csv\"", "\"../../q/out/h.csv\""},
                                 {"\"data/h.csv\"", "\"../../q/data/h.csv\""},
                                 {"\"fitted.rheo\"", "\"../../q/fitted.rheo\""}})
    expected.replace(expected.find(from), from.size(), to);
  CHECK(moved == expected);
  CHECK(relocated_source(kSource, "/p/q/a.rheo", "/p/q/other.rheo") == kSource);                                      // same folder
  CHECK(relocated_source(kSource, "/p/q/a.rheo", "/p/q/sub/b.rheo").find("\"../data/h.csv\"") != std::string::npos);  // one down
  CHECK(relocated_source(kSource, "/p/q/sub/../a.rheo", "/p/b.rheo").find("\"q/data/h.csv\"") != std::string::npos);  // one up, normalised
}

}  // namespace file_references_test
