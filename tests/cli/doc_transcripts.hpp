// Transcripts in the docs: a command as a user types it and what rheo prints, read from Markdown
// and compared with what the binary prints today (tests/cli/docs_transcripts_test.cpp runs them).
//
// The convention (docs/testing.md, "Transcripts in the docs"):
// - A transcript is a ```sh code block whose first line starts with `$ `. A line starting with `$ `
//   opens a command; the command runs on over the next lines until the shell accepts it as
//   complete (`bash -n`: an open quote, a trailing `|` or `\`, a `for` without its `done`). The
//   lines after it, up to the next `$ ` line or the end of the block, are its output: standard
//   output and standard error together, as a terminal shows them.
// - `<!-- docs-test: slow -->` on the line before the block marks a transcript that runs only when
//   RHEO_DOCS_SLOW=1 is set.
// - The transcripts of a document run in order from one scratch copy of the repository root, so
//   a command may read what an earlier one wrote; the tutorial's run in parts by its numbered
//   sections (`## N. ...`: 1-6, 7, 8-9, 10) and the slow ones on their own, so a command may use only
//   the files written before it in its part.
// - A line `...` (indented or not) stands for one or more lines left out; every other line must
//   appear, in order and with no line between it and its neighbours.
// - Text must be equal, except that a run of spaces counts as one. Numbers are compared by value:
//   an integer exactly; a decimal number to within one unit of its last printed digit or 1e-6 of
//   its value, whichever is larger (floating point may differ in the last digit between
//   machines); a number below 1e-9 in magnitude is rounding noise and matches any other such
//   number. Timings match any number: the X of `in X s`, and the last number of a row in a table
//   whose header line ends in `seconds`.
// - Progress lines (`rheo: ...: N evaluations, best objective X (stage), N s`), which rheo writes
//   every few seconds when standard error is no terminal and erases on a terminal, and the line
//   on what a fit's budget allows (`rheo: fit m: an evaluation takes about ...`), are left out
//   of what the command printed before comparing.
#pragma once

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace rheo::test::transcripts {

struct Transcript {
  int line = 0;         // of the `$ ` line in the document, 1-based
  std::string command;  // without the `$ `, continuation lines joined by '\n'
  std::vector<std::string> shown;
  bool slow = false;
  int section = 0;  // N of the last heading `## N. ...` before it; 0 before the first
};

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

inline std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

// The transcripts of a Markdown text. `complete(command)` says whether a command is complete
// shell (the tests ask `bash -n`). `stray` collects the lines `$ ...` in code blocks that are no
// transcript (a ``` block without `sh`, or a `$ ` line after other lines), which would escape
// the test.
inline std::vector<Transcript> parse(const std::string& markdown, const std::function<bool(const std::string&)>& complete,
                                     std::vector<int>* stray = nullptr) {
  const auto lines = lines_of(markdown);
  std::vector<Transcript> out;
  bool in_block = false, transcript = false, continuing = false, slow_next = false, slow = false;
  int section = 0;
  static const std::regex numbered_heading(R"(^## (\d+)\. )");
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    const int number = static_cast<int>(i) + 1;
    if (line.rfind("```", 0) == 0) {
      if (in_block) {
        in_block = false;
        continue;
      }
      in_block = true;
      slow = slow_next;
      transcript = line == "```sh" && i + 1 < lines.size() && lines[i + 1].rfind("$ ", 0) == 0;
      continuing = false;
      continue;
    }
    if (!in_block) {
      if (std::smatch m; std::regex_search(line, m, numbered_heading)) section = std::stoi(m[1]);
      if (!trimmed(line).empty()) slow_next = trimmed(line) == "<!-- docs-test: slow -->";
      continue;
    }
    if (!transcript) {
      if (line.rfind("$ ", 0) == 0 && stray != nullptr) stray->push_back(number);
      continue;
    }
    if (line.rfind("$ ", 0) == 0) {
      out.push_back(Transcript{number, line.substr(2), {}, slow, section});
      continuing = !complete(out.back().command);
    } else if (continuing) {
      out.back().command += "\n" + line;
      continuing = !complete(out.back().command);
    } else {
      out.back().shown.push_back(line);
    }
  }
  return out;
}

// A line cut into text and numbers; runs of spaces become one space.
struct Token {
  bool number = false;
  std::string text;
};

inline std::vector<Token> tokens(const std::string& line) {
  std::vector<Token> out;
  const auto add_text = [&out](const std::string& t) {
    if (!out.empty() && !out.back().number) {
      out.back().text += t;
    } else {
      out.push_back(Token{false, t});
    }
  };
  const auto digit = [&line](std::size_t k) { return k < line.size() && std::isdigit(static_cast<unsigned char>(line[k])) != 0; };
  const auto word = [&line](std::size_t k) { return std::isalnum(static_cast<unsigned char>(line[k])) != 0 || line[k] == '_'; };
  std::size_t i = 0;
  while (i < line.size()) {
    const char c = line[i];
    const bool after_word = i > 0 && (word(i - 1) || line[i - 1] == '.');
    if (std::isalpha(static_cast<unsigned char>(c)) != 0 || c == '_') {
      std::size_t j = i;
      while (j < line.size() && word(j)) ++j;
      add_text(line.substr(i, j - i));
      i = j;
    } else if (c == ' ') {
      while (i < line.size() && line[i] == ' ') ++i;
      add_text(" ");
    } else if (!after_word && (digit(i) || (c == '.' && digit(i + 1)) ||
                               ((c == '-' || c == '+') && (digit(i + 1) || (i + 1 < line.size() && line[i + 1] == '.' && digit(i + 2)))))) {
      std::size_t j = i;
      if (line[j] == '-' || line[j] == '+') ++j;
      while (digit(j)) ++j;
      if (j < line.size() && line[j] == '.' && digit(j + 1)) {
        ++j;
        while (digit(j)) ++j;
      }
      if (j < line.size() && (line[j] == 'e' || line[j] == 'E')) {
        std::size_t k = j + 1;
        if (k < line.size() && (line[k] == '-' || line[k] == '+')) ++k;
        if (digit(k)) {
          while (digit(k)) ++k;
          j = k;
        }
      }
      out.push_back(Token{true, line.substr(i, j - i)});
      i = j;
    } else {
      add_text(std::string(1, c));
      ++i;
    }
  }
  return out;
}

// Whether the number `actual` prints the number `shown` (the rules above; `timing`: any value).
inline bool number_matches(const std::string& shown, const std::string& actual, bool timing) {
  if (timing || shown == actual) return true;
  const double s = std::strtod(shown.c_str(), nullptr), a = std::strtod(actual.c_str(), nullptr);
  if (std::abs(s) < 1e-9 && std::abs(a) < 1e-9) return true;
  const auto exponent_at = shown.find_first_of("eE");
  const std::string mantissa = shown.substr(0, exponent_at);
  const auto point = mantissa.find('.');
  if (point == std::string::npos && exponent_at == std::string::npos) return false;  // an integer: exactly
  const int decimals = point == std::string::npos ? 0 : static_cast<int>(mantissa.size() - point - 1);
  const int exponent = exponent_at == std::string::npos ? 0 : std::atoi(shown.c_str() + exponent_at + 1);
  const double unit = std::pow(10.0, exponent - decimals);
  return std::abs(a - s) <= std::max(unit, 1e-6 * std::abs(s)) * (1 + 1e-9);
}

// Whether the printed `actual` line matches the `shown` one; `timing_column`: its last number is a
// timing (a row of a table headed `... seconds`).
inline bool line_matches(const std::string& shown, const std::string& actual, bool timing_column) {
  if (shown == actual) return true;
  const auto s = tokens(shown), a = tokens(actual);
  if (s.size() != a.size()) return false;
  std::size_t last_number = s.size();
  for (std::size_t k = 0; k < s.size(); ++k)
    if (s[k].number) last_number = k;
  static const std::regex before_timing(R"((^|\s)in\s$)"), after_timing(R"(^\ss\b.*)");
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (s[k].number != a[k].number) return false;
    if (!s[k].number) {
      if (s[k].text != a[k].text) return false;
      continue;
    }
    const bool in_x_s = k > 0 && k + 1 < s.size() && std::regex_search(s[k - 1].text, before_timing) && std::regex_match(s[k + 1].text, after_timing);
    if (!number_matches(s[k].text, a[k].text, in_x_s || (timing_column && k == last_number))) return false;
  }
  return true;
}

// rheo's periodic progress line (cli/progress.cpp), which a terminal shows as one line it erases,
// and the line on what a fit's budget allows (its figures are timings).
inline bool progress_line(const std::string& line) {
  static const std::regex progress(R"(^rheo: .*: \d+ evaluations, best objective \S+ \([^)]*\), \d+ s( of \S+ s)?(; the budget allows .* more)?$)");
  static const std::regex budget(
      R"(^rheo: .*: an evaluation takes about .*, so its budget of \d+ evaluations allows up to about .*; --time-limit or --max-evaluations bound it$)");
  return std::regex_match(line, progress) || std::regex_match(line, budget);
}

// What a transcript compares: the printed lines without progress lines and trailing blank lines.
inline std::vector<std::string> printed_lines(const std::string& output) {
  std::vector<std::string> out;
  for (auto& line : lines_of(output)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!progress_line(line)) out.push_back(line);
  }
  while (!out.empty() && trimmed(out.back()).empty()) out.pop_back();
  return out;
}

// Whether `actual` matches `shown`, with `...` lines standing for one or more lines each.
// Returns nothing on a match, else the first shown line (0-based) that no placement matched.
inline std::optional<std::size_t> mismatch(const std::vector<std::string>& shown, const std::vector<std::string>& actual) {
  std::vector<bool> timing(shown.size(), false);
  bool table = false;
  for (std::size_t k = 0; k < shown.size(); ++k) {
    timing[k] = table;
    const std::string t = trimmed(shown[k]);
    if (t.size() >= 7 && t.compare(t.size() - 7, 7, "seconds") == 0) table = true;
  }
  std::size_t furthest = 0;
  std::map<std::pair<std::size_t, std::size_t>, bool> memo;
  std::function<bool(std::size_t, std::size_t)> from = [&](std::size_t s, std::size_t a) -> bool {
    furthest = std::max(furthest, s);
    if (s == shown.size()) return a == actual.size();
    const auto key = std::make_pair(s, a);
    if (const auto hit = memo.find(key); hit != memo.end()) return hit->second;
    bool ok = false;
    if (trimmed(shown[s]) == "...") {
      for (std::size_t skip = a + 1; skip <= actual.size() && !ok; ++skip) ok = from(s + 1, skip);
    } else {
      ok = a < actual.size() && line_matches(shown[s], actual[a], timing[s]) && from(s + 1, a + 1);
    }
    memo[key] = ok;
    return ok;
  };
  if (from(0, 0)) return std::nullopt;
  return std::min(furthest, shown.empty() ? 0 : shown.size() - 1);
}

}  // namespace rheo::test::transcripts
