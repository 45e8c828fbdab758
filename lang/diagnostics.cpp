#include "lang/diagnostics.hpp"

#include "lang/limits.hpp"
#include "lang/text_encoding.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace rheo::lang {

void SourceSet::add(const std::string& file, std::string text) {
  Text& t = texts_[file];
  t.text = std::move(text);
  t.line_starts = {0};
  for (std::size_t i = 0; i < t.text.size(); ++i)
    if (t.text[i] == '\n') t.line_starts.push_back(i + 1);
}

std::string_view SourceSet::line(const std::string& file, int line) const {
  auto it = texts_.find(file);
  if (it == texts_.end() || line < 1 || static_cast<std::size_t>(line) > it->second.line_starts.size()) return {};
  const Text& t = it->second;
  const std::size_t start = t.line_starts[static_cast<std::size_t>(line) - 1];
  const std::size_t end = static_cast<std::size_t>(line) < t.line_starts.size() ? t.line_starts[static_cast<std::size_t>(line)] - 1 : t.text.size();
  std::string_view result = std::string_view(t.text).substr(start, end - start);
  if (!result.empty() && result.back() == '\r') result.remove_suffix(1);
  return result;
}

namespace {

// Bytes of a long source line shown around the column.
constexpr std::size_t kShownBytes = 160;

bool continuation_byte(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }

// The source line as shown under a message, and the caret line's indent: one space per
// character before the column (tabs kept), so that the caret stands under the column's
// character whatever its width in bytes.
struct Quote {
  std::string line, indent;
};
Quote quote(std::string_view source, int column) {
  const std::size_t at = std::min<std::size_t>(column > 0 ? static_cast<std::size_t>(column) - 1 : 0, source.size());
  std::size_t begin = 0, end = source.size();
  if (source.size() > kShownBytes) {
    begin = at > kShownBytes / 2 ? at - kShownBytes / 2 : 0;
    end = std::min(source.size(), begin + kShownBytes);
    while (begin > 0 && continuation_byte(source[begin])) --begin;
    while (end < source.size() && continuation_byte(source[end])) ++end;
  }
  Quote q;
  if (begin > 0) q.line = "...", q.indent = "   ";
  for (std::size_t i = begin; i < end;) {
    if (i < at) q.indent += source[i] == '\t' ? '\t' : ' ';
    i += append_printable_character(q.line, source, i);
  }
  if (end < source.size()) q.line += "...";
  return q;
}

}  // namespace

std::string format(const Diagnostic& d, const SourceSet& sources) {
  std::string out = fmt::format("{}:{}:{}: error: {}\n", d.where.file, d.where.line, d.where.column, d.message);
  std::string_view source = sources.line(d.where.file, d.where.line);
  if (source.empty() && d.where.line > 0) return out;
  const Quote q = quote(source, d.where.column);
  if (d.where.line > 0) out += fmt::format("  {}\n  {}^\n", q.line, q.indent);
  return out;
}

namespace {
// The first max_printed_errors diagnostics, then a count of the rest: a binary or mangled file
// can have one error per line, and a terminal full of them helps no one.
std::string format_all(const std::vector<Diagnostic>& diagnostics, const SourceSet& sources) {
  std::string out;
  const std::size_t shown = std::min(diagnostics.size(), max_printed_errors);
  for (std::size_t i = 0; i < shown; ++i) out += format(diagnostics[i], sources);
  if (diagnostics.size() > shown)
    out += fmt::format("... and {} more {}, not shown; fix the ones above first (is this the right file?)\n", diagnostics.size() - shown,
                       diagnostics.size() - shown == 1 ? "error" : "errors");
  return out;
}
}  // namespace

CompileError::CompileError(std::vector<Diagnostic> diagnostics, const SourceSet& sources)
    : ModelError(format_all(diagnostics, sources)), diagnostics_(std::move(diagnostics)) {}

}  // namespace rheo::lang
