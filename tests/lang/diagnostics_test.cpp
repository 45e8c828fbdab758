#include "lang/diagnostics.hpp"

#include <doctest/doctest.h>

using namespace rheo::lang;

TEST_CASE("format: location, message, source line and caret under the column") {
  SourceSet sources;
  sources.add("a.rheo", "line one\r\n\tsecond line\nthird");
  CHECK(sources.line("a.rheo", 1) == "line one");
  CHECK(sources.line("a.rheo", 3) == "third");
  CHECK(sources.line("a.rheo", 4).empty());
  CHECK(format({{"a.rheo", 2, 3}, "bad"}, sources) == "a.rheo:2:3: error: bad\n  \tsecond line\n  \t ^\n");
  CHECK(format({{"other.rheo", 1, 1}, "x"}, sources) == "other.rheo:1:1: error: x\n");
}

TEST_CASE("CompileError carries every diagnostic and the formatted text") {
  SourceSet sources;
  sources.add("a.rheo", "abc\n");
  CompileError e({{{"a.rheo", 1, 2}, "one"}, {{"a.rheo", 1, 3}, "two"}}, sources);
  CHECK(e.diagnostics().size() == 2);
  CHECK(std::string(e.what()) == "a.rheo:1:2: error: one\n  abc\n   ^\na.rheo:1:3: error: two\n  abc\n    ^\n");
}
