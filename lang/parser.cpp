// Actions of the grammar: each stores what its rule matched into the AST under construction.
// The single translation unit that instantiates PEGTL.
#include "lang/parser.hpp"

#include "lang/grammar.hpp"
#include "lang/grammar_errors.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cstdlib>

namespace rheo::lang {
namespace {

namespace g = grammar;
namespace pegtl = tao::pegtl;

// The AST under construction. Expressions are built on a stack: operands are pushed, operators
// pop their operands and push the combined node.
struct State {
  ast::File file;
  std::vector<ast::ExprPtr> exprs;
  std::vector<SourceLocation> operators;  // of pending binary operators
  std::vector<ast::Argument> arguments;   // the argument being parsed
  std::vector<ast::Element> elements;     // open elements, innermost last
  double number = 0.0;
  std::string unit;    // the last unit matched, consumed by the quantity or list it ends
  std::string string;  // the last string literal's contents

  ast::Simulate& simulate() { return file.simulations.back(); }
  ast::SettingValue& value() { return simulate().lines.back().settings.back().value; }
  ast::ExprPtr pop() {
    auto e = std::move(exprs.back());
    exprs.pop_back();
    return e;
  }
};

template <typename ActionInput>
SourceLocation where(const ActionInput& in) {
  const auto p = in.position();
  return {p.source, static_cast<int>(p.line), static_cast<int>(p.column)};
}

template <typename Rule>
struct action : pegtl::nothing<Rule> {};

// --- expressions ---
template <>
struct action<g::number> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.number = std::strtod(in.string().c_str(), nullptr);
  }
};
template <>
struct action<g::quantity> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    auto e = std::make_unique<ast::Expr>();
    e->kind = ast::Expr::Kind::number;
    e->number = s.number;
    e->unit = std::move(s.unit);
    s.unit.clear();
    e->where = where(in);
    s.exprs.push_back(std::move(e));
  }
};
template <>
struct action<g::unit> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.unit = in.string();
  }
};
template <>
struct action<g::reference> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    auto e = std::make_unique<ast::Expr>();
    e->kind = ast::Expr::Kind::reference;
    e->path = in.string();
    e->where = where(in);
    s.exprs.push_back(std::move(e));
  }
};
template <>
struct action<g::negation> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    auto e = std::make_unique<ast::Expr>();
    e->kind = ast::Expr::Kind::negate;
    e->lhs = s.pop();
    e->where = where(in);
    s.exprs.push_back(std::move(e));
  }
};

template <typename Sign>
struct operator_sign {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.operators.push_back(where(in));
  }
};
template <> struct action<g::times_sign> : operator_sign<g::times_sign> {};
template <> struct action<g::divide_sign> : operator_sign<g::divide_sign> {};
template <> struct action<g::plus_sign> : operator_sign<g::plus_sign> {};
template <> struct action<g::minus_sign> : operator_sign<g::minus_sign> {};

template <ast::Expr::Kind Kind>
struct binary {
  template <typename ActionInput>
  static void apply(const ActionInput&, State& s) {
    auto e = std::make_unique<ast::Expr>();
    e->kind = Kind;
    e->rhs = s.pop();
    e->lhs = s.pop();
    e->where = s.operators.back();
    s.operators.pop_back();
    s.exprs.push_back(std::move(e));
  }
};
template <> struct action<g::times> : binary<ast::Expr::Kind::multiply> {};
template <> struct action<g::divided> : binary<ast::Expr::Kind::divide> {};
template <> struct action<g::added> : binary<ast::Expr::Kind::add> {};
template <> struct action<g::subtracted> : binary<ast::Expr::Kind::subtract> {};

// --- arguments ---
template <>
struct action<g::argument_name> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.arguments.push_back({in.string(), nullptr, std::nullopt, where(in), {}});
  }
};
template <>
struct action<g::argument_value> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.arguments.back().value = s.pop();
    s.arguments.back().value_where = where(in);
  }
};
template <>
struct action<g::kw_in> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.arguments.back().bounds.emplace().where = where(in);
  }
};
template <>
struct action<g::bounds_lower> {
  template <typename ActionInput>
  static void apply(const ActionInput&, State& s) {
    s.arguments.back().bounds->lower = s.pop();
  }
};
template <>
struct action<g::bounds_upper> {
  template <typename ActionInput>
  static void apply(const ActionInput&, State& s) {
    s.arguments.back().bounds->upper = s.pop();
  }
};
struct close_argument {
  template <typename ActionInput>
  static void apply(const ActionInput&, State& s) {
    s.elements.back().arguments.push_back(std::move(s.arguments.back()));
    s.arguments.pop_back();
  }
};
template <> struct action<g::element_argument> : close_argument {};
template <> struct action<g::next_argument> : close_argument {};
template <>
struct action<g::param_argument> {
  template <typename ActionInput>
  static void apply(const ActionInput&, State& s) {
    s.file.models.back().parameters.push_back(std::move(s.arguments.back()));
    s.arguments.pop_back();
  }
};

// --- elements ---
template <>
struct action<g::element_kind> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    auto& e = s.elements.emplace_back();
    e.kind = in.string();
    e.where = where(in);
  }
};
template <>
struct action<g::block_kind> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    auto& e = s.elements.emplace_back();
    e.block = true;
    e.kind = in.string();
    e.where = where(in);
  }
};
template <>
struct action<g::element_name> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.elements.back().name = in.string();
    s.elements.back().name_where = where(in);
  }
};
// A finished element joins its parent block, or the model body at the outermost level.
struct close_element {
  template <typename ActionInput>
  static void apply(const ActionInput&, State& s) {
    ast::Element e = std::move(s.elements.back());
    s.elements.pop_back();
    auto& siblings = s.elements.empty() ? s.file.models.back().elements : s.elements.back().children;
    siblings.push_back(std::move(e));
  }
};
template <> struct action<g::leaf> : close_element {};
template <> struct action<g::block> : close_element {};

// --- top level ---
template <>
struct action<g::model_name> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    auto& m = s.file.models.emplace_back();
    m.name = in.string();
    m.where = where(in);
  }
};
template <>
struct action<g::import_name> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.file.imports.push_back({in.string(), where(in)});
  }
};
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
  static void apply(const ActionInput&, State& s) {
    s.simulate().lines.back().file = s.string;
  }
};
template <>
struct action<g::setting_key> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    auto& setting = s.simulate().lines.back().settings.emplace_back();
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
  }
};

// --- error reporting ---

// What stands at OFFSET of TEXT, for "found ..." in messages.
std::string describe_found(std::string_view text, std::size_t offset) {
  while (offset < text.size() && (text[offset] == ' ' || text[offset] == '\t')) ++offset;
  if (offset >= text.size()) return "end of file";
  auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.'; };
  if (text[offset] == '\n' || text[offset] == '\r') return "end of line";
  std::size_t end = offset;
  while (end < text.size() && word(text[end])) ++end;
  if (end == offset) ++end;
  return fmt::format("'{}'", text.substr(offset, end - offset));
}

std::string describe_element(const State& s) {
  if (s.elements.empty()) return "the element";
  const auto& e = s.elements.back();
  if (e.block) return e.name.empty() ? fmt::format("the '{}' block", e.kind) : fmt::format("'{} {}'", e.kind, e.name);
  return e.name.empty() ? fmt::format("'{}'", e.kind) : fmt::format("'{} {}'", e.kind, e.name);
}

void replace_all(std::string& text, std::string_view key, const std::string& value) {
  for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + value.size()))
    text.replace(at, key.size(), value);
}

template <typename Rule>
void run(const std::string& file_name, std::string_view text, State& state) {
  SourceSet sources;
  sources.add(file_name, std::string(text));
  pegtl::memory_input input(text.data(), text.size(), file_name);
  try {
    pegtl::parse<Rule, action, g::control>(input, state);
  } catch (const pegtl::parse_error& e) {
    const auto& p = e.positions().front();
    std::string message(e.message());
    replace_all(message, "{found}", describe_found(text, p.byte));
    replace_all(message, "{element}", describe_element(state));
    replace_all(message, "{model}", state.file.models.empty() ? std::string() : state.file.models.back().name);
    Diagnostic d{{file_name, static_cast<int>(p.line), static_cast<int>(p.column)}, message};
    throw CompileError({d}, sources);
  }
}

}  // namespace

ast::File parse(const std::string& file_name, std::string_view text) {
  State state;
  state.file.name = file_name;
  run<g::file>(file_name, text, state);
  return std::move(state.file);
}

ast::SettingNode parse_setting_text(const std::string& file_name, std::string_view text) {
  State state;
  state.file.simulations.emplace_back().lines.emplace_back();
  run<g::command_line_setting>(file_name, text, state);
  return std::move(state.simulate().lines.back().settings.back());
}

}  // namespace rheo::lang
