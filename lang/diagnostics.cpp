#include "lang/diagnostics.hpp"

#include <fmt/format.h>

namespace rheo::lang {

std::string_view SourceSet::line(const std::string& file, int line) const {
  auto it = texts_.find(file);
  if (it == texts_.end() || line < 1) return {};
  std::string_view text = it->second;
  std::size_t start = 0;
  for (int l = 1; l < line; ++l) {
    start = text.find('\n', start);
    if (start == std::string_view::npos) return {};
    ++start;
  }
  std::size_t end = text.find('\n', start);
  std::string_view result = text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start);
  if (!result.empty() && result.back() == '\r') result.remove_suffix(1);
  return result;
}

std::string format(const Diagnostic& d, const SourceSet& sources) {
  std::string out = fmt::format("{}:{}:{}: error: {}\n", d.where.file, d.where.line, d.where.column, d.message);
  std::string_view source = sources.line(d.where.file, d.where.line);
  if (source.empty() && d.where.line > 0) return out;
  // Tabs are kept in the caret line so the caret lines up under the column.
  std::string caret;
  for (int i = 0; i + 1 < d.where.column && i < static_cast<int>(source.size()); ++i) caret += source[i] == '\t' ? '\t' : ' ';
  if (d.where.line > 0) out += fmt::format("  {}\n  {}^\n", source, caret);
  return out;
}

namespace {
std::string format_all(const std::vector<Diagnostic>& diagnostics, const SourceSet& sources) {
  std::string out;
  for (const auto& d : diagnostics) out += format(d, sources);
  return out;
}
}  // namespace

CompileError::CompileError(std::vector<Diagnostic> diagnostics, const SourceSet& sources)
    : std::runtime_error(format_all(diagnostics, sources)), diagnostics_(std::move(diagnostics)) {}

}  // namespace rheo::lang
