#include "runtime/io/table_layout.hpp"

#include "lang/text_encoding.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/io/matlab_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <optional>

namespace rheo::runtime {
namespace {

[[noreturn]] void fail(const std::string& path, int row, int column, const std::string& message) {
  throw DataError(fmt::format("{}:{}:{}: error: {}", path, row, column, message));
}

bool blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

bool has_suffix(const std::string& path, std::string_view suffix) {
  return path.size() >= suffix.size() && lower(std::string_view(path).substr(path.size() - suffix.size())) == suffix;
}

void append_utf8(std::string& out, char32_t c) {
  if (c < 0x80) {
    out += static_cast<char>(c);
  } else if (c < 0x800) {
    out += static_cast<char>(0xC0 | (c >> 6));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else if (c < 0x10000) {
    out += static_cast<char>(0xE0 | (c >> 12));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (c >> 18));
    out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  }
}

// UTF-16 after its byte-order mark, little- or big-endian; an unpaired surrogate is U+FFFD.
std::string utf16_to_utf8(std::string_view bytes, bool little_endian) {
  std::string out;
  out.reserve(bytes.size() / 2);
  auto unit = [&](std::size_t i) {
    const auto lo = static_cast<unsigned char>(bytes[little_endian ? i : i + 1]);
    const auto hi = static_cast<unsigned char>(bytes[little_endian ? i + 1 : i]);
    return static_cast<char32_t>(lo | (hi << 8));
  };
  for (std::size_t i = 0; i + 1 < bytes.size(); i += 2) {
    char32_t c = unit(i);
    if (c >= 0xD800 && c < 0xDC00 && i + 3 < bytes.size() && unit(i + 2) >= 0xDC00 && unit(i + 2) < 0xE000) {
      c = 0x10000 + ((c - 0xD800) << 10) + (unit(i + 2) - 0xDC00);
      i += 2;
    } else if (c >= 0xD800 && c < 0xE000) {
      c = 0xFFFD;
    }
    append_utf8(out, c);
  }
  return out;
}

struct Line {
  std::size_t begin, end;  // without the line end
  int row;
};

std::vector<Line> lines_of(std::string_view text) {
  std::vector<Line> lines;
  std::size_t start = 0;
  int row = 1;
  while (start < text.size()) {
    auto newline = text.find('\n', start);
    if (newline == std::string_view::npos) newline = text.size();
    lines.push_back({start, newline, row++});
    start = newline + 1;
  }
  return lines;
}

// The step name without a trailing " - N" counter: "Amplitude sweep - 1" -> "Amplitude sweep".
std::string without_counter(std::string_view name) {
  std::string_view base = trim(name);
  const auto dash = base.rfind(" - ");
  if (dash != std::string_view::npos && dash + 3 < base.size() &&
      std::all_of(base.begin() + static_cast<std::ptrdiff_t>(dash + 3), base.end(),
                  [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
    base = base.substr(0, dash);
  return std::string(base);
}

std::string quoted_list(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "\"" : ", \"") + lang::printable(n) + "\"";
  return out;
}

TableLayout trios_layout(const std::string& path, std::string_view text, const std::vector<Line>& lines, const std::string& step) {
  struct Step {
    std::string name;
    std::size_t line;  // index of the names row in LINES
  };
  std::vector<Step> steps;
  int bare_step_row = 0;  // a [step] line with nothing after it
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (is_step_line(text.substr(lines[i].begin, lines[i].end - lines[i].begin))) {
      if (i + 1 >= lines.size()) {
        bare_step_row = lines[i].row;
        continue;
      }
      const std::string_view name_line = text.substr(lines[i + 1].begin, lines[i + 1].end - lines[i + 1].begin);
      steps.push_back({std::string(trim(name_line.substr(0, name_line.find('\t')))), i + 2});
    }
  if (steps.empty())
    fail(path, bare_step_row, 1, "this TRIOS export's [step] line is its last: no step follows it; export the file again, or remove the line");
  TableLayout layout;
  for (const auto& s : steps) layout.steps.push_back(s.name);
  const Step* chosen = nullptr;
  if (step.empty() && steps.size() == 1) chosen = &steps.front();
  for (const auto& s : steps)
    if (!step.empty() && (lower(s.name) == lower(trim(step)) || lower(without_counter(s.name)) == lower(without_counter(step)))) {
      chosen = &s;
      break;
    }
  if (!chosen && step.empty())
    fail(path, 1, 1,
         fmt::format("this TRIOS export has {} steps ({}); pick the one to read on the data line, e.g. step = \"{}\"", steps.size(),
                     quoted_list(layout.steps), lang::printable(without_counter(steps.front().name))));
  if (!chosen)
    fail(path, 1, 1, fmt::format("this TRIOS export has no step \"{}\"; its steps are {}", lang::printable(step), quoted_list(layout.steps)));
  if (chosen->line + 1 >= lines.size())
    fail(path, lines.back().row, 1,
         fmt::format("the TRIOS step \"{}\" has no names and units rows; export the step again", lang::printable(chosen->name)));
  std::size_t last = chosen->line + 1;
  while (last + 1 < lines.size()) {
    const std::string_view next = trim(text.substr(lines[last + 1].begin, lines[last + 1].end - lines[last + 1].begin));
    if (next.empty() || next.front() == '[') break;
    ++last;
  }
  const Line& names = lines[chosen->line];
  layout.begin = names.begin;
  layout.end = lines[last].end;
  layout.first_row = names.row;
  layout.delimiter = detect_delimiter(text.substr(names.begin, names.end - names.begin));
  layout.decimal_comma = layout.delimiter != ',';
  layout.units_row = true;
  layout.step = chosen->name;
  return layout;
}

}  // namespace

void refuse_workbook(const std::string& path, std::string_view start) {
  constexpr std::string_view zip = "PK\x03\x04", ole = "\xD0\xCF\x11\xE0", hdf5 = "\x89HDF";
  if (start.starts_with(hdf5))
    fail(path, 1, 1,
         "this is an HDF5 file, not a text table; rheo reads HDF5 histories from files named .h5 or .hdf5: rename it (docs/data-formats.md, "
         "\"HDF5 files\")");
  if (const MatHeader mat = matlab_header(start); mat != MatHeader::none)
    fail(path, 1, 1,
         mat == MatHeader::v73 ? "this is a MATLAB v7.3 MAT-file, not a text table; rheo reads one as a history when its name ends in .mat: "
                                 "rename it (docs/data-formats.md, \"MATLAB files\")"
                               : "this is a MATLAB v5/v7 MAT-file, not a text table; re-save it in MATLAB as v7.3 and name it .mat "
                                 "(save('run.mat', 't', 'x', 'F', '-v7.3')), or export the history as a CSV table");
  const bool workbook = start.starts_with(zip) || start.starts_with(ole);
  if (workbook || has_suffix(path, ".xlsx") || has_suffix(path, ".xls") || has_suffix(path, ".xlsm") || has_suffix(path, ".ods"))
    fail(path, 1, 1,
         "this is a spreadsheet workbook, not a text table; export the sheet as CSV or text (in Excel: File > Save As > CSV UTF-8) and "
         "give that file");
}

bool is_utf16(std::string_view start) { return start.starts_with("\xFF\xFE") || start.starts_with("\xFE\xFF"); }

std::string text_as_utf8(const std::string& path, std::string text) {
  refuse_workbook(path, text);
  if (text.rfind("\xFF\xFE", 0) == 0) return utf16_to_utf8(std::string_view(text).substr(2), true);
  if (text.rfind("\xFE\xFF", 0) == 0) return utf16_to_utf8(std::string_view(text).substr(2), false);
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);
  return text;
}

char detect_delimiter(std::string_view names_row) {
  std::array<std::size_t, 3> counts{};  // tab, ';', ','
  bool quoted = false;
  for (char c : names_row) {
    if (c == '"') quoted = !quoted;
    if (quoted) continue;
    if (c == '\t') ++counts[0];
    else if (c == ';') ++counts[1];
    else if (c == ',') ++counts[2];
  }
  constexpr std::array<char, 3> delimiters{'\t', ';', ','};
  std::size_t best = 2;
  for (std::size_t i = 0; i < 3; ++i)
    if (counts[i] > counts[best] || (counts[i] == counts[best] && counts[i] > 0 && i < best)) best = i;
  return delimiters[best];
}

void split_cells(std::string_view line, char delimiter, std::vector<Cell>& cells, std::string& scratch) {
  cells.clear();
  scratch.clear();
  scratch.reserve(line.size());  // unescaped text is never longer than its line: views into SCRATCH stay valid
  std::size_t start = 0;
  while (true) {
    std::size_t i = start;
    while (i < line.size() && (line[i] == ' ' || (line[i] == '\t' && delimiter != '\t'))) ++i;
    std::string_view text;
    std::size_t end = i;
    if (i < line.size() && line[i] == '"') {  // a quoted cell: delimiters inside are text
      std::size_t j = i + 1;
      const std::size_t close = line.find('"', j);
      if (close == std::string_view::npos || close + 1 >= line.size() || line[close + 1] != '"') {
        // No "" inside: the text between the quotes, as written.
        text = line.substr(j, (close == std::string_view::npos ? line.size() : close) - j);
        j = close == std::string_view::npos ? line.size() : close + 1;
      } else {
        const std::size_t first = scratch.size();
        while (j < line.size()) {
          if (line[j] == '"' && j + 1 < line.size() && line[j + 1] == '"') {
            scratch += '"';
            j += 2;
          } else if (line[j] == '"') {
            ++j;
            break;
          } else {
            scratch += line[j++];
          }
        }
        text = std::string_view(scratch).substr(first);
      }
      end = line.find(delimiter, j);
      if (end == std::string_view::npos) end = line.size();
    } else {
      end = start;  // cells are short: a loop, not memchr
      while (end < line.size() && line[end] != delimiter) ++end;
      text = trim(line.substr(start, end - start));
    }
    cells.push_back({text, static_cast<int>(start) + 1});
    if (end >= line.size()) break;
    start = end + 1;
  }
}

bool is_step_line(std::string_view line) {
  const std::string_view word = trim(line);
  constexpr std::string_view step = "[step]";
  if (word.size() != step.size()) return false;
  for (std::size_t i = 0; i < step.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(word[i])) != step[i]) return false;
  return true;
}

bool holds_layout(std::string_view line) {
  const std::string_view content = trim(line);
  return !content.empty() && content.front() != '#';
}

TableLayout plain_layout(std::string_view line) {
  TableLayout layout;
  layout.delimiter = detect_delimiter(trim(line));
  layout.decimal_comma = layout.delimiter != ',';
  return layout;
}

TableLayout find_layout(const std::string& path, std::string_view text, const std::string& step) {
  std::optional<std::string_view> first;  // the first line holding the layout
  for (std::size_t start = 0; start < text.size();) {
    std::size_t newline = text.find('\n', start);
    if (newline == std::string_view::npos) newline = text.size();
    const std::string_view line = text.substr(start, newline - start);
    if (is_step_line(line)) return trios_layout(path, text, lines_of(text), step);
    if (!first && holds_layout(line)) first = line;
    start = newline + 1;
  }
  if (!step.empty())
    fail(path, 1, 1,
         fmt::format("step = \"{}\" picks a step of a TRIOS export, but this file has no [step] sections; remove step from the data line",
                     lang::printable(step)));
  TableLayout layout = first ? plain_layout(*first) : TableLayout{};
  layout.end = text.size();
  return layout;
}

}  // namespace rheo::runtime
