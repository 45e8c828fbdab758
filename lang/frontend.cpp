#include "lang/frontend.hpp"

#include "lang/checker.hpp"
#include "lang/fit_schema.hpp"
#include "lang/names.hpp"
#include "lang/parser.hpp"
#include "lang/protocol_schema.hpp"
#include "lang/stdlib.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <list>
#include <set>
#include <sstream>
#include <stdexcept>

namespace rheo::lang {

Program load_program(const std::string& path) {
  auto unreadable = [&](const std::string& reason) {
    return UnreadableSource(fmt::format("{}: error: cannot read it ({}); check the path", path, reason));
  };
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw unreadable("it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw unreadable(std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw unreadable(std::strerror(errno));
  return compile_source(path, text.str());
}

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

}  // namespace rheo::lang
