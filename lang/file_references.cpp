#include "lang/file_references.hpp"

#include "lang/parser.hpp"

#include <algorithm>
#include <filesystem>

namespace rheo::lang {
namespace {

namespace fs = std::filesystem;

// The name held by the string literal whose opening quote is at byte QUOTE.
FileReference literal_at(int quote, const std::string& name) { return {quote + 1, quote + 1 + static_cast<int>(name.size()), name}; }

// The folder a file's relative names are read from, absolute and lexically normal.
fs::path folder_of(const std::string& file) { return fs::absolute(fs::path(file)).parent_path().lexically_normal(); }

}  // namespace

std::vector<FileReference> file_references(const std::string& file_name, std::string_view text) {
  const ast::File file = parse(file_name, text);
  std::vector<FileReference> out;
  for (const auto& simulation : file.simulations)
    for (const auto& line : simulation.lines) {
      if (line.output && line.file_begin >= 0) out.push_back(literal_at(line.file_begin, line.file));
      for (const auto& setting : line.settings)
        if (setting.key == "file" && setting.value.kind == ast::SettingValue::Kind::string)
          out.push_back(literal_at(setting.value.begin, setting.value.text));
    }
  for (const auto& fit : file.fits)
    for (const auto& line : fit.lines)
      if (line.kind != ast::FitLine::Kind::settings && line.file_begin >= 0) out.push_back(literal_at(line.file_begin, line.file));
  std::sort(out.begin(), out.end(), [](const FileReference& a, const FileReference& b) { return a.begin < b.begin; });
  return out;
}

std::string relocated_source(std::string_view text, const std::string& from_file, const std::string& to_file) {
  const fs::path from = folder_of(from_file), to = folder_of(to_file);
  std::string out(text);
  if (from == to) return out;
  const std::vector<FileReference> references = file_references(from_file, text);
  for (auto it = references.rbegin(); it != references.rend(); ++it) {  // from the back, so earlier ranges stay put
    const fs::path name(it->name);
    if (name.empty() || name.is_absolute()) continue;
    const fs::path target = (from / name).lexically_normal();
    fs::path moved = target.lexically_relative(to);
    if (moved.empty()) moved = target;  // no relative way (another root): the absolute name
    out.replace(static_cast<std::size_t>(it->begin), static_cast<std::size_t>(it->end - it->begin), moved.generic_string());
  }
  return out;
}

}  // namespace rheo::lang
