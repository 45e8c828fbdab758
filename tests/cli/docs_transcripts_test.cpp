// The transcripts of docs/tutorial.md, README.md and docs/cli.md (a ```sh block of `$ ` commands
// and what they print; the convention is in doc_transcripts.hpp and docs/testing.md) against the
// binary: each command runs as a user runs it, from a scratch copy of the repository's root
// (examples/ without the files commands write, and build/rheo), in order, and what it prints
// must be what the document shows. A stale number fails here until the document is regenerated.
// Transcripts marked slow run only with RHEO_DOCS_SLOW=1.
#include "cli_support.hpp"
#include "doc_transcripts.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace docs_transcripts_test {

namespace fs = std::filesystem;
using namespace rheo::test::transcripts;

namespace {

std::string shell_output(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::array<char, 4096> buffer{};
  while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) out.append(buffer.data(), n);
  pclose(pipe);
  return out;
}

// Whether COMMAND is complete shell: bash parses it (`bash -n`) and it ends in no line continuation.
bool complete_shell(const std::string& command) {
  if (!command.empty() && command.back() == '\\') return false;
  const fs::path file = rheo::test::scratch_directory("transcripts") / "parse.sh";
  std::ofstream(file, std::ios::binary) << command << "\n";
  return std::system(fmt::format("bash -n '{}' 2>/dev/null", file.string()).c_str()) == 0;
}

// The generated files of examples/ (examples/.gitignore), which a scratch root starts without.
bool generated(const fs::path& file) {
  const std::string name = file.filename().string();
  for (const char* suffix : {"_fitted.rheo", "_refined.rheo", "_yeoh.rheo", ".csv", ".html", ".svg", ".png"})
    if (name.ends_with(suffix)) return true;
  return false;
}

// A scratch repository root for DOC's commands: examples/ (its data and its sources, not what
// commands wrote there), build/rheo, the binary under test, and fmusim's source.
fs::path scratch_root(const std::string& doc) {
  const fs::path root = rheo::test::scratch_directory("transcripts") / doc;
  fs::remove_all(root);
  fs::create_directories(root / "examples");
  fs::create_directories(root / "build");
  fs::copy(fs::path(RHEO_EXAMPLES_DIR) / "data", root / "examples" / "data", fs::copy_options::recursive);
  for (const auto& entry : fs::directory_iterator(RHEO_EXAMPLES_DIR))
    if (entry.is_regular_file() && !generated(entry.path())) fs::copy_file(entry.path(), root / "examples" / entry.path().filename());
  fs::create_symlink(fs::absolute(RHEO_BINARY), root / "build" / "rheo");
  fs::create_directories(root / "tests" / "third_party");  // fmusim's source, which the FMU section builds
  fs::create_directory_symlink(fs::path(RHEO_SOURCE_DIR) / "tests" / "third_party" / "fmusim", root / "tests" / "third_party" / "fmusim");
  return root;
}

// What COMMAND prints run in ROOT by bash, standard error merged into standard output, with
// build/ on PATH (docs/cli.md writes `rheo`) and the C locale.
std::string run_in(const fs::path& root, const std::string& command) {
  const fs::path script = root.parent_path() / (root.filename().string() + ".sh");
  std::ofstream(script, std::ios::binary) << "exec 2>&1\n" << command << "\n";
  return shell_output(fmt::format("cd '{}' && LC_ALL=C PATH='{}':\"$PATH\" bash '{}'", root.string(), (root / "build").string(), script.string()));
}

std::string numbered(const std::vector<std::string>& lines) {
  std::string out;
  for (std::size_t k = 0; k < lines.size(); ++k) out += fmt::format("{:4} | {}\n", k + 1, lines[k]);
  return out;
}

bool slow_wanted() {
  const char* value = std::getenv("RHEO_DOCS_SLOW");
  return value != nullptr && std::string(value) == "1";
}

// The transcripts of a document that one test case runs: those of its numbered sections FIRST
// to LAST whose slowness is SLOW.
struct Part {
  int first = 0, last = 1000;
  bool slow = false;
};

// Runs the transcripts of DOC (relative to the repository) in PART, in order, in one scratch
// root; returns how many ran.
int check_transcripts(const std::string& doc, Part part = {}) {
  std::vector<int> stray;
  const auto all = parse(rheo::test::read_required(fs::path(RHEO_SOURCE_DIR) / doc), complete_shell, &stray);
  for (const int line : stray) FAIL_CHECK(doc << ":" << line << ": a `$ ` command outside a ```sh transcript escapes this test");
  const fs::path root = scratch_root(fmt::format("{}-{}-{}{}", fs::path(doc).stem().string(), part.first, part.last, part.slow ? "-slow" : ""));
  int ran = 0;
  std::optional<bool> jq;
  for (const auto& t : all) {
    if (t.slow != part.slow || t.section < part.first || t.section > part.last) continue;
    if (t.command.find("jq ") != std::string::npos) {
      if (!jq) jq = rheo::test::tool_installed("jq", "jq");
      if (!*jq) continue;
    }
    ++ran;
    const auto actual = printed_lines(run_in(root, t.command));
    if (const auto at = mismatch(t.shown, actual)) {
      FAIL_CHECK(fmt::format("{}:{}: `{}` prints other than the document shows; first unmatched shown line {}: `{}`\nshown:\n{}printed:\n{}", doc,
                             t.line, t.command, *at + 1, t.shown.empty() ? "" : t.shown[*at], numbered(t.shown), numbered(actual)));
    }
  }
  fs::remove_all(rheo::test::scratch_directory("transcripts"));  // the root and the scripts
  return ran;
}

}  // namespace

TEST_CASE("docs transcripts: a sh block of command lines splits into commands, their output and the slow marker") {
  const std::string md =
      "text\n```sh\n$ a |\n  b\nout 1\n...\n$ c\n```\n## 3. S\n<!-- docs-test: slow -->\n\n```sh\n$ d\nx\n```\n```\n$ e\n```\n```sh\nf\n$ g\n```\n";
  const auto complete = [](const std::string& c) { return c.back() != '|'; };
  std::vector<int> stray;
  const auto t = parse(md, complete, &stray);
  REQUIRE(t.size() == 3);
  CHECK(t[0].line == 3);
  CHECK(t[0].command == "a |\n  b");
  CHECK(t[0].shown == std::vector<std::string>{"out 1", "..."});
  CHECK_FALSE(t[0].slow);
  CHECK(t[1].command == "c");
  CHECK(t[1].shown.empty());
  CHECK(t[2].command == "d");
  CHECK(t[2].slow);
  CHECK(t[0].section == 0);
  CHECK(t[2].section == 3);
  CHECK(stray == std::vector<int>{17, 21});
  CHECK(complete_shell("echo a"));
  CHECK_FALSE(complete_shell("echo a |"));
  CHECK_FALSE(complete_shell("for s in a; do echo $s"));
  CHECK_FALSE(complete_shell("echo 'a"));
  CHECK_FALSE(complete_shell("echo a \\"));
  fs::remove_all(rheo::test::scratch_directory("transcripts"));
}

TEST_CASE("docs transcripts: text must be equal and numbers agree to their printed digits") {
  CHECK(line_matches("  phi (5.1) = 0.0740262, err (6.1) = 1.4949e-03", "  phi (5.1) = 0.0740263, err (6.1) = 1.4950e-03", false));
  CHECK_FALSE(line_matches("err (6.1) = 1.4949e-03", "err (6.1) = 1.4951e-03", false));  // two units of the last digit
  CHECK_FALSE(line_matches("err (6.1) = 1.4949e-03", "err (6.1) = 1.4949e-04", false));
  CHECK_FALSE(line_matches("182 points", "183 points", false));  // integers exactly
  CHECK_FALSE(line_matches("phi (5.1) = 0.07", "phi (6.1) = 0.07", false));
  CHECK_FALSE(line_matches("worst point 2 mm, 3 Hz", "worst point 3 mm, 45 Hz", false));
  CHECK_FALSE(line_matches("stiffness +0.99 %", "stiffness -0.99 %", false));
  CHECK_FALSE(line_matches("m1.k  16.2393", "m2.k  16.2393", false));  // identifiers are text
  CHECK_FALSE(line_matches("status FTOL_REACHED", "status NO_DESCENT", false));
  CHECK(line_matches("m1.k      10       16.2393  N/mm", "m1.k      10      16.23935  N/mm", false));  // spaces, 1e-6 of the value
  CHECK(line_matches("54.27343061644 N", "54.27343061648 N", false));
  CHECK(line_matches("phi (5.1) = 6.80258e-18, err (6.1) = 1.9910e-11", "phi (5.1) = 2.1e-19, err (6.1) = 3.5e-12", false));
  CHECK(line_matches("3357 evaluations in 0.90 s; optimizer status NO_DESCENT", "3357 evaluations in 12.5 s; optimizer status NO_DESCENT", false));
  CHECK_FALSE(line_matches("3357 evaluations in 0.90 s; x", "3358 evaluations in 0.90 s; x", false));
  CHECK(line_matches("   1   2   7    1.4949e-03      0.30", "   1   2   7    1.4949e-03     10.30", true));
  CHECK_FALSE(line_matches("   1   2   7    1.4949e-03      0.30", "   1   2   7    1.4959e-03      0.30", true));
  CHECK_FALSE(line_matches("   1   2   7    1.4949e-03      0.30", "   1   2   7    1.4949e-03     10.30", false));  // not in a table
}

TEST_CASE("docs transcripts: ... stands for one or more lines, progress lines are dropped") {
  const std::vector<std::string> printed = printed_lines(
      "a\nrheo: fit coupled: 2 evaluations, best objective 0.0113057 (sample), 8 s\nb 1\n"
      "rheo: fit coupled: an evaluation takes about 1.5 ms, so its budget of 20000 evaluations allows up to about 30 s; --time-limit or "
      "--max-evaluations bound it\nc\nrheo: fit coupled: 9 evaluations, best objective 0.01 (local), 9 s of 60 s; the budget allows 12 min more\nd\n\n");
  CHECK(printed == std::vector<std::string>{"a", "b 1", "c", "d"});
  CHECK_FALSE(mismatch({"a", "b 1", "c", "d"}, printed));
  CHECK_FALSE(mismatch({"a", "...", "d"}, printed));
  CHECK_FALSE(mismatch({"...", "c", "  ..."}, printed));
  CHECK(mismatch({"a", "...", "b 1", "c", "d"}, printed) == 2u);  // ... leaves out at least one line
  CHECK(mismatch({"a", "c", "d"}, printed) == 1u);                // no line may be left out silently
  CHECK(mismatch({"a", "b 1"}, printed) == 1u);                   // nor at the end
  CHECK(mismatch({"a", "...", "e"}, printed) == 2u);
  CHECK(mismatch({"a", "b 2", "..."}, printed) == 1u);
  CHECK_FALSE(mismatch({}, {}));
  CHECK(mismatch({"a"}, {}) == 0u);
}

TEST_CASE("docs transcripts: the commands of docs/tutorial.md sections 1-6 print what it shows") {
  CHECK(check_transcripts("docs/tutorial.md", {1, 6}) >= 25);
}

TEST_CASE("docs transcripts: the commands of docs/tutorial.md section 7 print what it shows") {
  CHECK(check_transcripts("docs/tutorial.md", {7, 7}) >= 3);
}

TEST_CASE("docs transcripts: the commands of docs/tutorial.md sections 8-9 print what it shows") {
  CHECK(check_transcripts("docs/tutorial.md", {8, 9}) >= 8);
}

TEST_CASE("docs transcripts: the commands of docs/tutorial.md section 10 (the FMU in fmusim) print what it shows") {
  CHECK(check_transcripts("docs/tutorial.md", {10, 10}) >= 7);
}

TEST_CASE("docs transcripts: the slow commands of docs/tutorial.md print what it shows (with RHEO_DOCS_SLOW=1)") {
  if (!slow_wanted()) {
    MESSAGE("SKIPPED: set RHEO_DOCS_SLOW=1 to run the tutorial's slow transcripts");
    return;
  }
  CHECK(check_transcripts("docs/tutorial.md", {0, 1000, true}) >= 1);
}

TEST_CASE("docs transcripts: the commands of README.md print what it shows") { CHECK(check_transcripts("README.md") >= 3); }

TEST_CASE("docs transcripts: the commands of docs/cli.md print what it shows") { CHECK(check_transcripts("docs/cli.md") >= 4); }

}  // namespace docs_transcripts_test
