// The parser's state and the actions that build models: expressions, arguments, elements,
// models and imports. A private part of parser.cpp, the one translation unit that includes it.
#pragma once

#include "lang/ast.hpp"
#include "lang/grammar.hpp"
#include "lang/limits.hpp"

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

namespace rheo::lang::parsing {

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
  std::string unit;                                   // the last unit matched, consumed by the quantity or list it ends
  std::string string;                                 // the last string literal's contents
  std::vector<ast::SettingNode>* settings = nullptr;  // of the directive line being parsed
  // Expression levels open around the operand being parsed: parentheses, unary minus and
  // operators whose right operand it is (limits.hpp).
  int open_levels = 0;

  // Room for the grammar's nesting guards (grammar.hpp, limits.hpp). At a block's start every
  // open element is a block.
  bool room(g::block_nesting) const { return static_cast<int>(elements.size()) < max_block_depth; }
  // The group and at least one operand inside it.
  bool room(g::group_nesting) const { return open_levels + 2 <= max_expression_depth; }
  // The operator's node over the operand before it.
  bool room(g::operator_nesting) const { return open_levels + exprs.back()->depth + 1 <= max_expression_depth; }

  ast::Simulate& simulate() { return file.simulations.back(); }
  ast::Fit& fit() { return file.fits.back(); }
  ast::SettingValue& value() { return settings->back().value; }
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

// Byte offset of the match's start in the source text.
template <typename ActionInput>
int byte_offset(const ActionInput& in) {
  return static_cast<int>(in.position().byte);
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
// Parentheses, unary minus and operators open a level until their operand is complete.
struct open_level {
  template <typename ActionInput>
  static void apply(const ActionInput&, State& s) {
    ++s.open_levels;
  }
};
template <>
struct action<g::paren_open> : open_level {};
template <>
struct action<g::negative_sign> : open_level {};
template <>
struct action<g::paren_close> {
  template <typename ActionInput>
  static void apply(const ActionInput&, State& s) {
    --s.open_levels;
    ++s.exprs.back()->depth;
  }
};
template <>
struct action<g::negation> {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    auto e = std::make_unique<ast::Expr>();
    e->kind = ast::Expr::Kind::negate;
    e->lhs = s.pop();
    e->depth = e->lhs->depth + 1;
    e->where = where(in);
    s.exprs.push_back(std::move(e));
    --s.open_levels;
  }
};

template <typename Sign>
struct operator_sign {
  template <typename ActionInput>
  static void apply(const ActionInput& in, State& s) {
    s.operators.push_back(where(in));
    ++s.open_levels;
  }
};
template <>
struct action<g::times_sign> : operator_sign<g::times_sign> {};
template <>
struct action<g::divide_sign> : operator_sign<g::divide_sign> {};
template <>
struct action<g::plus_sign> : operator_sign<g::plus_sign> {};
template <>
struct action<g::minus_sign> : operator_sign<g::minus_sign> {};

template <ast::Expr::Kind Kind>
struct binary {
  template <typename ActionInput>
  static void apply(const ActionInput&, State& s) {
    auto e = std::make_unique<ast::Expr>();
    e->kind = Kind;
    e->rhs = s.pop();
    e->lhs = s.pop();
    e->depth = std::max(e->lhs->depth, e->rhs->depth) + 1;
    e->where = s.operators.back();
    s.operators.pop_back();
    s.exprs.push_back(std::move(e));
    --s.open_levels;
  }
};
template <>
struct action<g::times> : binary<ast::Expr::Kind::multiply> {};
template <>
struct action<g::divided> : binary<ast::Expr::Kind::divide> {};
template <>
struct action<g::added> : binary<ast::Expr::Kind::add> {};
template <>
struct action<g::subtracted> : binary<ast::Expr::Kind::subtract> {};

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
    s.arguments.back().value_begin = byte_offset(in);
    s.arguments.back().value_end = byte_offset(in) + static_cast<int>(in.size());
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
template <>
struct action<g::element_argument> : close_argument {};
template <>
struct action<g::next_argument> : close_argument {};
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
template <>
struct action<g::leaf> : close_element {};
template <>
struct action<g::block> : close_element {};

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

}  // namespace rheo::lang::parsing
