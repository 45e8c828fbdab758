// Actions of the directive rules (simulate and fit blocks), error reporting and the entry
// points. The single translation unit that instantiates PEGTL; the model actions are in
// parser_actions.hpp.
#include "lang/parser.hpp"

#include "lang/grammar.hpp"
#include "lang/grammar_errors.hpp"
#include "lang/parser_actions.hpp"
#include "lang/text_encoding.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <string_view>

namespace rheo::lang {
namespace parsing {

// --- simulate blocks ---
template <>
struct action<g::kw_simulate> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.file.simulations.emplace_back().where = where(in);
  }
};
template <>
struct action<g::simulate_model> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.simulate().model = in.string();
    s.simulate().model_where = where(in);
  }
};

// --- directives ---
template <>
struct action<g::string_body> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.string = in.string();
    s.string.pop_back();  // the closing quote
  }
};
template <>
struct action<g::protocol_kind> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    auto& line = s.simulate().lines.emplace_back();
    line.kind = in.string();
    line.where = where(in);
    s.settings = &line.settings;
  }
};
template <>
struct action<g::kw_output> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    auto& line = s.simulate().lines.emplace_back();
    line.output = true;
    line.where = where(in);
  }
};
template <>
struct action<g::output_file> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.simulate().lines.back().file = s.string;
    s.simulate().lines.back().file_begin = byte_offset(in);
  }
};
template <>
struct action<g::setting_key> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    auto& setting = s.settings->emplace_back();
    setting.key = in.string();
    setting.where = where(in);
  }
};
template <>
struct action<g::setting_string> {
  template <typename ActionInput>
  static void apply(const ActionInput&, State& s) {
    s.value().kind = ast::SettingValue::Kind::string;
    s.value().text = s.string;
  }
};
template <>
struct action<g::list_item> {
  template <typename ActionInput>
  static void apply(const ActionInput&, State& s) {
    s.value().kind = ast::SettingValue::Kind::list;
    s.value().items.push_back(s.pop());
  }
};
template <>
struct action<g::list_unit> {
  template <typename ActionInput>
  static void apply(const ActionInput&, State& s) {
    s.value().unit = std::move(s.unit);
    s.unit.clear();
  }
};
template <>
struct action<g::single_value> {
  template <typename ActionInput>
  static void apply(const ActionInput&, State& s) {
    s.value().kind = ast::SettingValue::Kind::expression;
    s.value().items.push_back(s.pop());
  }
};
template <>
struct action<g::range_tail> {
  template <typename ActionInput>
  static void apply(const ActionInput&, State& s) {
    auto step = s.pop();
    auto end = s.pop();
    s.value().kind = ast::SettingValue::Kind::range;
    s.value().items.push_back(s.pop());
    s.value().items.push_back(std::move(end));
    s.value().items.push_back(std::move(step));
  }
};
template <>
struct action<g::setting_value> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.value().where = where(in);
    s.value().begin = byte_offset(in);
    s.value().end = byte_offset(in) + static_cast<int>(in.size());
  }
};

// --- fit blocks ---
template <>
struct action<g::kw_fit> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.file.fits.emplace_back().where = where(in);
  }
};
template <>
struct action<g::fit_model> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.fit().model = in.string();
    s.fit().model_where = where(in);
  }
};
template <ast::FitLine::Kind Kind>
struct open_fit_line {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    auto& line = s.fit().lines.emplace_back();
    line.kind = Kind;
    line.where = where(in);
    s.settings = &line.settings;
  }
};
template <>
struct action<g::fit_data_keyword> : open_fit_line<ast::FitLine::Kind::data> {};
template <>
struct action<g::fit_output_keyword> : open_fit_line<ast::FitLine::Kind::output> {};
template <>
struct action<g::fit_settings_begin> : open_fit_line<ast::FitLine::Kind::settings> {};
struct fit_line_file {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.fit().lines.back().file = s.string;
    s.fit().lines.back().file_where = where(in);
    s.fit().lines.back().file_begin = byte_offset(in);
  }
};
template <>
struct action<g::fit_data_file> : fit_line_file {};
template <>
struct action<g::fit_data_line> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.fit().lines.back().end = byte_offset(in) + static_cast<int>(in.size());
  }
};
template <>
struct action<g::fit_output_file> : fit_line_file {};
template <>
struct action<g::command_line_data_name> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.string = in.string();
    s.string.erase(s.string.find_last_not_of(" \t") + 1);  // the blanks before the comma
    fit_line_file::apply(in, s);
  }
};

// --- error reporting ---
namespace {

// What stands at OFFSET of TEXT, for "found ..." in messages: a word, one character, or what
// is no text (the file is valid UTF-8 by then, see run()).
std::string describe_found(std::string_view text, std::size_t offset) {
  while (offset < text.size() && (text[offset] == ' ' || text[offset] == '\t')) ++offset;
  if (offset >= text.size()) return "end of file";
  auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.'; };
  if (text[offset] == '\n' || text[offset] == '\r') return "end of line";
  const auto byte = static_cast<unsigned char>(text[offset]);
  if (byte < 0x20 || byte == 0x7F) return fmt::format("control character 0x{:02X}", byte);
  std::size_t end = offset;
  while (end < text.size() && word(text[end])) ++end;
  if (end == offset) end += std::max<std::size_t>(utf8_length(text, offset), 1);
  return fmt::format("'{}'", printable(text.substr(offset, end - offset)));
}

// A word right after a number on its line that the unit table does not know ("1 Nmm"): the
// grammar stopped at it, but what the writer needs to hear is that it is no unit. Empty when
// the word at OFFSET is not such a word.
std::string unknown_unit_hint(std::string_view text, std::size_t offset) {
  while (offset < text.size() && (text[offset] == ' ' || text[offset] == '\t')) ++offset;
  // A unit written with the micro sign, "1 µm", "1 N*s/µm" (the grammar stops at the µ, or at
  // the '/' before it): the whole unit, from after the number to the next separator.
  std::size_t unit_start = offset, unit_end = offset;
  const auto in_unit = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '*' || c == '/' || c == '^' || c == '_' || c == '-'; };
  while (unit_start > 0 && in_unit(text[unit_start - 1])) --unit_start;
  while (unit_start < offset && (std::isdigit(static_cast<unsigned char>(text[unit_start])) || text[unit_start] == '.')) ++unit_start;
  while (unit_end < text.size() && std::string_view(" \t\r\n,;)]}").find(text[unit_end]) == std::string_view::npos) ++unit_end;
  const std::string_view written = text.substr(unit_start, unit_end - unit_start);
  if (const std::string ascii = ascii_micro_spelling(written); !ascii.empty())
    return fmt::format("; rheo reads units in ASCII, with u for micro: write '{}' for '{}'", ascii, printable(written));
  std::size_t end = offset;
  while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '_')) ++end;
  if (end == offset || !std::isalpha(static_cast<unsigned char>(text[offset]))) return {};
  std::size_t before = offset;
  while (before > 0 && (text[before - 1] == ' ' || text[before - 1] == '\t')) --before;
  if (before == 0 || !(std::isdigit(static_cast<unsigned char>(text[before - 1])) || text[before - 1] == '.')) return {};
  const std::string_view word = text.substr(offset, end - offset);
  if (unit_atom(word)) return {};
  return fmt::format("; '{}' is not a unit rheo knows: use {}, combined with '*', '/' and '^' (e.g. N/mm, N*s/mm)", printable(word), unit_names());
}

std::string describe_element(const State& s) {
  if (s.elements.empty()) return "the element";
  const auto& e = s.elements.back();
  if (e.block) return e.name.empty() ? fmt::format("the '{}' block", e.kind) : fmt::format("'{} {}'", e.kind, e.name);
  return e.name.empty() ? fmt::format("'{}'", e.kind) : fmt::format("'{} {}'", e.kind, e.name);
}

void replace_all(std::string& text, std::string_view key, const std::string& value) {
  for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + value.size())) text.replace(at, key.size(), value);
}

template <typename Rule>
void run(const std::string& file_name, std::string_view text, State& state) {
  auto fail = [&](int line, int column, const std::string& message) {
    SourceSet sources;
    sources.add(file_name, std::string(text));
    throw CompileError({{{file_name, line, column}, message}}, sources);
  };
  if (const auto problem = find_encoding_problem(text)) {
    const TextPosition p = position_of(text, problem->offset);
    fail(p.line, p.column, problem->description);
  }
  pegtl::memory_input input(text.data(), text.size(), file_name);
  try {
    pegtl::parse<Rule, action, g::control>(input, state);
  } catch (const pegtl::parse_error& e) {
    const auto& p = e.positions().front();
    std::string message(e.message());
    replace_all(message, "{found}", describe_found(text, p.byte));
    replace_all(message, "{element}", describe_element(state));
    replace_all(message, "{model}", state.file.models.empty() ? std::string() : state.file.models.back().name);
    message += unknown_unit_hint(text, p.byte);
    fail(static_cast<int>(p.line), static_cast<int>(p.column), message);
  }
}

}  // namespace
}  // namespace parsing

ast::File parse(const std::string& file_name, std::string_view text) {
  parsing::State state;
  state.file.name = file_name;
  parsing::run<grammar::file>(file_name, text, state);
  return std::move(state.file);
}

ast::SettingNode parse_setting_text(const std::string& file_name, std::string_view text) {
  parsing::State state;
  std::vector<ast::SettingNode> settings;
  state.settings = &settings;
  parsing::run<grammar::command_line_setting>(file_name, text, state);
  return std::move(settings.back());
}

ast::FitLine parse_data_text(const std::string& file_name, std::string_view text) {
  parsing::State state;
  ast::FitLine& line = state.file.fits.emplace_back().lines.emplace_back();
  line.kind = ast::FitLine::Kind::data;
  line.where = {file_name, 1, 1};
  state.settings = &line.settings;
  parsing::run<grammar::command_line_data>(file_name, text, state);
  return std::move(state.file.fits.back().lines.back());
}

}  // namespace rheo::lang
