#include "lang/diagnostics.hpp"

#include "lang/limits.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

namespace diagnostics_test {

using namespace rheo::lang;

namespace {

// FORMAT of a diagnostic at FILE:LINE:COLUMN. Diagnostics here are named objects: GCC 12 at -O3
// misreads the string of a braced temporary as maybe uninitialised (-Wmaybe-uninitialized).
std::string formatted(const std::string& file, int line, int column, const std::string& message, const SourceSet& sources) {
  const Diagnostic diagnostic{SourceLocation{file, line, column}, message};
  return format(diagnostic, sources);
}

}  // namespace

TEST_CASE("format: location, message, source line and caret under the column") {
  SourceSet sources;
  sources.add("a.rheo", "line one\r\n\tsecond line\nthird");
  CHECK(sources.line("a.rheo", 1) == "line one");
  CHECK(sources.line("a.rheo", 3) == "third");
  CHECK(sources.line("a.rheo", 4).empty());
  CHECK(formatted("a.rheo", 2, 3, "bad", sources) == "a.rheo:2:3: error: bad\n  \tsecond line\n  \t ^\n");
  CHECK(formatted("other.rheo", 1, 1, "x", sources) == "other.rheo:1:1: error: x\n");
}

TEST_CASE("CompileError carries every diagnostic and the formatted text") {
  SourceSet sources;
  sources.add("a.rheo", "abc\n");
  const Diagnostic one{SourceLocation{"a.rheo", 1, 2}, "one"}, two{SourceLocation{"a.rheo", 1, 3}, "two"};
  CompileError e({one, two}, sources);
  CHECK(e.diagnostics().size() == 2);
  CHECK(std::string(e.what()) == "a.rheo:1:2: error: one\n  abc\n   ^\na.rheo:1:3: error: two\n  abc\n    ^\n");
}

TEST_CASE("CompileError prints the first max_printed_errors diagnostics, then how many more, keeping every one") {
  SourceSet sources;
  sources.add("a.rheo", "abc\n");
  const Diagnostic bad{SourceLocation{"a.rheo", 1, 2}, "bad"};
  for (const std::size_t count : {max_printed_errors, max_printed_errors + 1, max_printed_errors + 7}) {
    CAPTURE(count);
    const std::vector<Diagnostic> all(count, bad);
    const CompileError e(all, sources);
    CHECK(e.diagnostics().size() == count);
    const std::string text = e.what();
    std::size_t printed = 0;
    for (auto at = text.find("a.rheo:1:2: error: bad"); at != std::string::npos; at = text.find("a.rheo:1:2: error: bad", at + 1)) ++printed;
    CHECK(printed == max_printed_errors);
    const std::size_t cut = count - max_printed_errors;
    const std::string tail = cut == 0 ? "" : cut == 1 ? "... and 1 more error, not shown" : fmt::format("... and {} more errors, not shown", cut);
    CHECK((tail.empty() ? text.find("... and") == std::string::npos : text.find(tail) != std::string::npos));
  }
}

TEST_CASE("format: the caret stands under the column's character after multi-byte characters") {
  SourceSet sources;
  sources.add("u.rheo", "# µ—x\n");
  // Byte column 7 is 'x': '#', ' ', µ (2 bytes) and — (3 bytes) stand before it, four characters.
  CHECK(formatted("u.rheo", 1, 7, "here", sources) == "u.rheo:1:7: error: here\n  # µ—x\n      ^\n");
}

TEST_CASE("format: bytes that are not text are shown as U+FFFD, never raw") {
  SourceSet sources;
  sources.add("b.rheo", std::string("ab\xff\x1b[2J\0c\n", 10));
  const std::string text = formatted("b.rheo", 1, 3, "bad byte", sources);
  CHECK(text ==
        "b.rheo:1:3: error: bad byte\n  ab\xEF\xBF\xBD\xEF\xBF\xBD[2J\xEF\xBF\xBD"
        "c\n    ^\n");
}

TEST_CASE("format: a long line is shown around the column, diagnostics on a 10 MB line stay cheap") {
  std::string line(10'000'000, 'a');
  line[5'000'000] = 'X';
  SourceSet sources;
  sources.add("long.rheo", line + "\nsecond\n");
  const std::string text = formatted("long.rheo", 1, 5'000'001, "here", sources);
  CHECK(text.size() < 500);
  const std::size_t quoted = text.find('\n') + 3;              // the quoted line, after its indent
  const std::size_t caret_line = text.find('\n', quoted) + 3;  // the caret line, after its indent
  CHECK(text.compare(quoted, 3, "...") == 0);
  CHECK(text.compare(caret_line - 6, 6, "...\n  ") == 0);
  CHECK(text[quoted + (text.find('^', caret_line) - caret_line)] == 'X');       // the caret stands under 'X'
  for (int i = 0; i < 100000; ++i) formatted("long.rheo", 2, 1, "x", sources);  // the line index makes this instant
  CHECK(formatted("long.rheo", 2, 1, "x", sources) == "long.rheo:2:1: error: x\n  second\n  ^\n");
}

}  // namespace diagnostics_test
