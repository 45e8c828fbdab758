// Text -> syntax tree (ast.hpp). Parse errors are fatal at the first one: they throw
// CompileError holding exactly one Diagnostic. Text that is not UTF-8 (text_encoding.hpp) and
// nesting past limits.hpp are parse errors too, so the tree returned is within those limits.
#pragma once

#include "lang/ast.hpp"
#include "lang/diagnostics.hpp"

#include <string>
#include <string_view>

namespace rheo::lang {

ast::File parse(const std::string& file_name, std::string_view text);

// One `KEY = VALUE` setting as written on a command line (file name "<command line>").
ast::SettingNode parse_setting_text(const std::string& file_name, std::string_view text);

// A data file and a data line's settings as written on a command line,
// `sweep.txt, step = "Amplitude sweep"` (grammar::command_line_data): a data FitLine.
ast::FitLine parse_data_text(const std::string& file_name, std::string_view text);

}  // namespace rheo::lang
