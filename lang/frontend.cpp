#include "lang/frontend.hpp"

#include "lang/checker.hpp"
#include "lang/file_text.hpp"
#include "lang/fit_schema.hpp"
#include "lang/limits.hpp"
#include "lang/names.hpp"
#include "lang/parser.hpp"
#include "lang/protocol_schema.hpp"
#include "lang/stdlib.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <list>
#include <set>
#include <stdexcept>

namespace rheo::lang {

std::string read_source(const std::string& path) {
  FileText source = read_file_text(path, max_source_bytes);
  if (!source.failure.empty()) throw UnreadableSource(fmt::format("{}: error: cannot read it ({}); {}", path, source.failure, source.advice()));
  // A byte-order mark (some Windows editors write one) is no text: dropped here, so that
  // columns and the byte offsets of source edits refer to the same text.
  if (source.text.starts_with("\xEF\xBB\xBF")) source.text.erase(0, 3);
  return std::move(source.text);
}

Program load_program(const std::string& path) { return compile_source(path, read_source(path)); }

Program compile_source(const std::string& file_name, std::string_view text) {
  SourceSet sources;
  sources.add(file_name, std::string(text));
  std::vector<Diagnostic> errors;
  const ast::File file = parse(file_name, text);

  // Imports, including those of imported modules, each module once.
  std::list<ast::File> modules;  // stable addresses
  std::set<std::string> seen;
  std::vector<const ast::File*> pending{&file};
  while (!pending.empty()) {
    const ast::File* f = pending.back();
    pending.pop_back();
    for (const auto& import : f->imports) {
      if (!seen.insert(import.name).second) continue;
      auto source = stdlib_source(import.name);
      if (!source) {
        errors.push_back({import.where, fmt::format("unknown import '{}';{} the standard library has: {}", import.name,
                                                    did_you_mean(import.name, stdlib_names()), join(stdlib_names()))});
        continue;
      }
      const std::string path = stdlib_path(import.name);
      sources.add(path, std::string(*source));
      pending.push_back(&modules.emplace_back(parse(path, *source)));
    }
  }
  std::vector<const ast::File*> imported;
  for (const auto& m : modules) imported.push_back(&m);

  Program program = check(file, imported, errors);
  if (!errors.empty()) {
    std::stable_sort(errors.begin(), errors.end(), [](const Diagnostic& a, const Diagnostic& b) {
      return std::tie(a.where.file, a.where.line, a.where.column) < std::tie(b.where.file, b.where.line, b.where.column);
    });
    throw CompileError(std::move(errors), sources);
  }
  return program;
}

namespace {
using SettingCheck = std::function<std::optional<Setting>(const ast::SettingNode&, std::vector<Diagnostic>&)>;

Setting parse_command_line_setting(std::string_view text, const SettingCheck& check) {
  const std::string file_name = "<command line>";
  SourceSet sources;
  sources.add(file_name, std::string(text));
  const ast::SettingNode node = parse_setting_text(file_name, text);
  std::vector<Diagnostic> errors;
  auto setting = check(node, errors);
  if (!setting || !errors.empty()) throw CompileError(std::move(errors), sources);
  return *setting;
}
}  // namespace

Setting parse_setting(ProtocolKind kind, std::string_view text) {
  return parse_command_line_setting(
      text, [kind](const ast::SettingNode& node, std::vector<Diagnostic>& errors) { return check_setting(kind, node, errors); });
}

Setting parse_fit_setting(std::string_view text) { return parse_command_line_setting(text, check_fit_setting); }

FitData parse_data_option(std::string_view text) {
  const std::string file_name = "<command line>";
  if (text.find(',') == std::string_view::npos) {
    FitData plain;
    plain.file = std::string(text);
    plain.where = {file_name, 1, 1};
    return plain;
  }
  SourceSet sources;
  sources.add(file_name, std::string(text));
  const ast::FitLine line = parse_data_text(file_name, text);
  std::vector<Diagnostic> errors;
  FitData data = check_data_line(line, errors);
  if (!errors.empty()) throw CompileError(std::move(errors), sources);
  return data;
}

}  // namespace rheo::lang
