// The one table of parse error messages, keyed by the grammar rule that failed under must<>.
// Placeholders, substituted by the parser when the error is reported:
//   {found}    what stands at the error position ("'}'", "end of file", "'spring'")
//   {element}  the innermost element being parsed ("'maxwell m1'", "the 'parallel' block")
//   {model}    the model being parsed
#pragma once

#include "lang/grammar.hpp"

namespace rheo::lang::grammar {

struct errors {
  template <typename Rule>
  static constexpr const char* message = nullptr;
};

// clang-format off
template <> inline constexpr const char* errors::message<block_room> = "blocks nested deeper than 200 levels; flatten the network (a series block directly inside a series block, or a parallel inside a parallel, can be merged into it)";
template <> inline constexpr const char* errors::message<group_room> = "expression nested deeper than 200 levels (each pair of parentheses, unary minus and operator is one); simplify it or compute parts of it in `param` declarations";
template <> inline constexpr const char* errors::message<operator_room> = errors::message<group_room>;
template <> inline constexpr const char* errors::message<string_body> = "unterminated string literal; close it with '\"' on the same line";
template <> inline constexpr const char* errors::message<paren_expression> = "expected an expression after '(', found {found}";
template <> inline constexpr const char* errors::message<paren_close> = "expected ')' to close the parenthesized expression, found {found}";
template <> inline constexpr const char* errors::message<operand> = "expected a number, a parameter name or '(' after the operator, found {found}";
template <> inline constexpr const char* errors::message<term_operand> = "expected a number, a parameter name or '(' after the operator, found {found}";
template <> inline constexpr const char* errors::message<bounds_open> = "expected '[' after 'in' to open the bounds [LO, HI], found {found}";
template <> inline constexpr const char* errors::message<bounds_lower> = "expected the lower bound after 'in [', found {found}";
template <> inline constexpr const char* errors::message<bounds_comma> = "expected ',' between the lower and upper bound, found {found}";
template <> inline constexpr const char* errors::message<bounds_upper> = "expected the upper bound after ',', found {found}";
template <> inline constexpr const char* errors::message<bounds_close> = "expected ']' to close the bounds [LO, HI], found {found}";
template <> inline constexpr const char* errors::message<argument_equals> = "expected '=' after the parameter name, found {found}";
template <> inline constexpr const char* errors::message<argument_value> = "expected a value (e.g. 5 N/mm) after '=', found {found}";
template <> inline constexpr const char* errors::message<next_argument> = "expected a parameter `NAME = VALUE` after ',' in the argument list of {element}, found {found}";
template <> inline constexpr const char* errors::message<param_argument> = "expected `NAME = VALUE` after 'param', found {found}";
template <> inline constexpr const char* errors::message<arguments_close> = "expected ')' to close the argument list of {element}, found {found}";
template <> inline constexpr const char* errors::message<leaf_open_ahead> = "expected '(' to open the argument list of {element}, found {found}";
template <> inline constexpr const char* errors::message<block_open> = "expected '{' to open {element}, found {found}";
template <> inline constexpr const char* errors::message<block_close> = "expected an element or '}' to close {element}, found {found}";
template <> inline constexpr const char* errors::message<model_name> = "expected a model name after 'model', found {found}";
template <> inline constexpr const char* errors::message<model_open> = "expected '{' to open the body of model '{model}', found {found}";
template <> inline constexpr const char* errors::message<model_close> = "expected an element, a 'param' declaration or '}' to close model '{model}', found {found}";
template <> inline constexpr const char* errors::message<import_name> = "expected a model name after 'import', found {found}";
template <> inline constexpr const char* errors::message<list_item> = "expected a value in the list after ',', found {found}";
template <> inline constexpr const char* errors::message<list_close> = "expected ',' or ']' to close the list, found {found}";
template <> inline constexpr const char* errors::message<range_end> = "expected the end of the range after '..', found {found}";
template <> inline constexpr const char* errors::message<range_step_keyword> = "expected 'step' after the end of the range (FROM .. TO step STEP), found {found}";
template <> inline constexpr const char* errors::message<range_step> = "expected the step of the range after 'step', found {found}";
template <> inline constexpr const char* errors::message<setting> = "expected a setting `KEY = VALUE`, found {found}";
template <> inline constexpr const char* errors::message<protocol_file_key> = "a protocol's file is a setting: write `file = \"NAME.csv\"` (e.g. history file = \"drive.csv\"), found {found}";
template <> inline constexpr const char* errors::message<protocol_setting_alone> = "a setting needs its protocol: a simulate block's line starts with its protocol (harmonic, static, quasistatic, history, step) and its settings follow it, each after a ',' (e.g. harmonic frequency = [10] Hz, amplitude = [1] mm, solver = fixed); or a ',' is missing before the setting, found {found}";
template <> inline constexpr const char* errors::message<setting_equals> = "expected '=' after the setting name, found {found}";
template <> inline constexpr const char* errors::message<setting_value> = "expected a value, a list [..], a range FROM .. TO step STEP or a \"string\" after '=', found {found}";
template <> inline constexpr const char* errors::message<output_file> = "expected a file name in double quotes after 'output', found {found}";
template <> inline constexpr const char* errors::message<simulate_open> = "expected '{' to open the simulate block, found {found}";
template <> inline constexpr const char* errors::message<simulate_close> = "expected a protocol line, 'output' or '}' to close the simulate block, found {found}";
template <> inline constexpr const char* errors::message<fit_open> = "expected '{' to open the fit block, found {found}";
template <> inline constexpr const char* errors::message<fit_close> = "expected a setting `KEY = VALUE`, `data \"FILE\"`, `output \"FILE\"` or '}' to close the fit block, found {found}";
template <> inline constexpr const char* errors::message<fit_data_file> = "expected the data file name in double quotes after 'data', e.g. data \"specimen_harmonic.csv\", found {found}";
template <> inline constexpr const char* errors::message<fit_output_file> = "expected a file name in double quotes after 'output' for the fitted model, e.g. output \"fitted.rheo\", found {found}";
template <> inline constexpr const char* errors::message<file_end> = "expected 'import', 'model', 'simulate' or 'fit' at the top level, found {found}";
template <> inline constexpr const char* errors::message<setting_end> = "unexpected text after the setting value: {found}";
template <> inline constexpr const char* errors::message<command_line_data_file> = "expected the data file name before the first ',' (or in double quotes), found {found}";
template <> inline constexpr const char* errors::message<command_line_data_end> = "expected ', KEY = VALUE' (a data line's setting) or the end after the file name or a setting, found {found}";
// clang-format on

// must_if raises for a rule with a message wherever it fails, so messages go only to rules
// used solely under must<>. Rules under must<> that can never fail (sep, star, opt) need none.
template <typename Rule>
using control = tao::pegtl::must_if<errors, tao::pegtl::normal, false>::control<Rule>;

}  // namespace rheo::lang::grammar
