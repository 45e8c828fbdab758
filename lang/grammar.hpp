// The rheo grammar (PEGTL). One rule per concept; actions (parser.cpp) build the AST;
// every must<> point has its message in grammar_errors.hpp.
//
//   file      := sep (import | model | simulate | fit)* eof
//   import    := 'import' NAME
//   model     := 'model' NAME '{' (param | element)* '}'
//   param     := 'param' argument
//   element   := ('parallel'|'series') [NAME] '{' element* '}'  |  KIND [NAME] '(' [argument (',' argument)*] ')'
//   argument  := PATH '=' expression ['in' '[' expression ',' expression ']']
//   simulate  := 'simulate' [NAME] '{' (output | protocol)* '}'
//   protocol  := KIND setting (',' setting)*          output := 'output' STRING
//   fit       := 'fit' [NAME] '{' (data | output | setting (',' setting)*)* '}'
//   data      := 'data' STRING (',' setting)*           ('data' is reserved only there)
//   setting   := KEY '=' (STRING | list | expression ['..' expression 'step' expression])
//   list      := '[' expression (',' expression)* ']' [UNIT]
//   expression:= term (('+'|'-') term)*   term := factor (('*'|'/') factor)*
//   factor    := '-' factor | '(' expression ')' | NUMBER [UNIT] | PATH
//   command line (grammar of --set, --data): setting  |  (NAME-TO-FIRST-COMMA | STRING) (',' setting)*
// Statements are not newline-terminated: every statement starts with a keyword or a name that
// cannot continue the previous expression (expressions continue only with an operator).
// Blocks and expressions nest at most as deep as limits.hpp allows (the *_room guards).
#pragma once

#include "lang/units.hpp"

#include <tao/pegtl.hpp>

#include <string_view>

namespace rheo::lang::grammar {

namespace pegtl = tao::pegtl;
using namespace pegtl;

// --- limits --------------------------------------------------------------------------------
// A guard of limits.hpp: consumes nothing and succeeds while the parser state has room for one
// more level of Nesting (`state.room(Nesting{})`). It stands under must<> before the rule that
// nests, so that going deeper is reported at that rule's first character instead of recursing.
template <typename Nesting>
struct room {
  using rule_t = room;
  using subs_t = type_list<>;
  template <apply_mode, rewind_mode, template <typename...> class, template <typename...> class, typename ParseInput, typename State>
  static bool match(ParseInput&, const State& state) {
    return state.room(Nesting{});
  }
};
struct block_nesting {};     // a block in the open blocks
struct group_nesting {};     // parentheses or a unary minus around the operand to come
struct operator_nesting {};  // a binary operator over the operand just parsed
struct block_room : room<block_nesting> {};
struct group_room : room<group_nesting> {};
struct operator_room : room<operator_nesting> {};

// --- lexical -------------------------------------------------------------------------------
struct comment : seq<one<'#'>, until<eolf>> {};
struct sep : star<sor<ascii::space, comment>> {};

struct kw_import : TAO_PEGTL_KEYWORD("import") {};
struct kw_model : TAO_PEGTL_KEYWORD("model") {};
struct kw_simulate : TAO_PEGTL_KEYWORD("simulate") {};
struct kw_param : TAO_PEGTL_KEYWORD("param") {};
struct kw_parallel : TAO_PEGTL_KEYWORD("parallel") {};
struct kw_series : TAO_PEGTL_KEYWORD("series") {};
struct kw_in : TAO_PEGTL_KEYWORD("in") {};
struct kw_step : TAO_PEGTL_KEYWORD("step") {};
struct kw_output : TAO_PEGTL_KEYWORD("output") {};
struct kw_fit : TAO_PEGTL_KEYWORD("fit") {};
struct keyword : sor<kw_import, kw_model, kw_simulate, kw_param, kw_parallel, kw_series, kw_in, kw_step, kw_output, kw_fit> {};

struct name : seq<not_at<keyword>, identifier> {};
struct path : list<identifier, one<'.'>> {};

// 12, 1.5, 4., .5, 1e-3 ; a '.' followed by '.' belongs to a range, not the number.
struct exponent : seq<one<'e', 'E'>, opt<one<'+', '-'>>, plus<digit>> {};
struct fraction : seq<one<'.'>, not_at<one<'.'>>, star<digit>> {};
struct number : seq<sor<seq<plus<digit>, opt<fraction>>, seq<one<'.'>, plus<digit>>>, opt<exponent>> {};

// A word of the unit table (units.hpp), or `%`. `in` (inch) is not a unit when it opens bounds `in [`.
struct unit_word {
  using rule_t = unit_word;
  using subs_t = type_list<>;
  template <typename ParseInput>
  static bool match(ParseInput& in) {
    std::size_t n = 0;
    if (in.size(1) >= 1 && in.peek_char(0) == '%') {
      in.bump_in_this_line(1);
      return true;
    }
    while (n < in.size(n + 1) && is_word_char(in.peek_char(n))) ++n;
    if (n == 0) return false;
    std::string_view word(in.current(), n);
    if (!unit_atom(word)) return false;
    if (word == "in") {
      std::size_t k = n;
      while (k < in.size(k + 1) && (in.peek_char(k) == ' ' || in.peek_char(k) == '\t' || in.peek_char(k) == '\n' || in.peek_char(k) == '\r')) ++k;
      if (k < in.size(k + 1) && in.peek_char(k) == '[') return false;
    }
    in.bump_in_this_line(n);
    return true;
  }
  static bool is_word_char(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'; }
};
struct unit_power : seq<one<'^'>, opt<one<'-'>>, plus<digit>> {};
struct unit_factor : seq<unit_word, opt<unit_power>> {};
struct unit : seq<unit_factor, star<one<'*', '/'>, unit_factor>> {};

struct string_open : one<'"'> {};
struct string_body : until<one<'"'>, not_one<'\n', '\r'>> {};
struct string_literal : seq<string_open, must<string_body>> {};

// --- expressions ---------------------------------------------------------------------------
struct expression;
struct quantity_unit : seq<sep, unit> {};
struct quantity : seq<number, opt<quantity_unit>> {};
struct reference : path {};
struct paren_open : one<'('> {};
struct paren_close : one<')'> {};
struct paren_expression;
struct parenthesized : if_must<at<paren_open>, group_room, paren_open, sep, paren_expression, sep, paren_close> {};
struct factor;
struct negative_sign : one<'-'> {};
struct operand;
struct negation : if_must<at<negative_sign>, group_room, negative_sign, sep, operand> {};
struct factor : sor<negation, parenthesized, quantity, reference> {};
struct operand : factor {};
struct times_sign : one<'*'> {};
struct divide_sign : one<'/'> {};
struct plus_sign : one<'+'> {};
struct minus_sign : one<'-'> {};
template <typename Sign, typename Operand>
struct binary_operation : if_must<seq<sep, at<Sign>>, operator_room, Sign, sep, Operand> {};
struct times : binary_operation<times_sign, operand> {};
struct divided : binary_operation<divide_sign, operand> {};
struct term : seq<factor, star<sor<times, divided>>> {};
struct term_operand : term {};
struct added : binary_operation<plus_sign, term_operand> {};
struct subtracted : binary_operation<minus_sign, term_operand> {};
struct expression : seq<term, star<sor<added, subtracted>>> {};
struct paren_expression : expression {};

// --- arguments and elements ----------------------------------------------------------------
struct bounds_open : one<'['> {};
struct bounds_comma : one<','> {};
struct bounds_close : one<']'> {};
struct bounds_lower : expression {};
struct bounds_upper : expression {};
struct bounds : if_must<seq<sep, kw_in>, sep, bounds_open, sep, bounds_lower, sep, bounds_comma, sep, bounds_upper, sep, bounds_close> {};
struct argument_name : path {};
struct argument_equals : one<'='> {};
struct argument_value : expression {};
struct argument : seq<argument_name, sep, must<argument_equals>, sep, must<argument_value>, opt<bounds>> {};
struct element_argument : argument {};
struct param_argument : argument {};
struct next_argument : argument {};

struct argument_next : if_must<seq<sep, one<','>>, sep, next_argument> {};
struct arguments_close : one<')'> {};
struct argument_list : seq<one<'('>, sep, opt<element_argument, star<argument_next>>, sep, must<arguments_close>> {};
struct element_kind : name {};
struct element_name : name {};
struct leaf_open : one<'('> {};
struct leaf_header : seq<element_kind, opt<sep, element_name>> {};
struct leaf_open_ahead : at<leaf_open> {};
struct leaf : seq<leaf_header, sep, must<leaf_open_ahead>, argument_list> {};

struct element;
struct block_kind : sor<kw_parallel, kw_series> {};
struct block_open : one<'{'> {};
struct block_close : one<'}'> {};
struct block_header : seq<block_kind, opt<sep, element_name>> {};
struct block : if_must<at<block_kind>, block_room, block_header, sep, block_open, star<sep, element>, sep, block_close> {};
struct element : sor<block, leaf> {};

// --- models --------------------------------------------------------------------------------
struct param_decl : if_must<kw_param, sep, param_argument> {};
struct model_name : name {};
struct model_open : one<'{'> {};
struct model_close : one<'}'> {};
struct model_item : sor<param_decl, element> {};
struct model_decl : if_must<kw_model, sep, model_name, sep, model_open, star<sep, model_item>, sep, model_close> {};

struct import_name : name {};
struct import_decl : if_must<kw_import, sep, import_name> {};

// --- directives ----------------------------------------------------------------------------
struct list_open : one<'['> {};
struct list_item : expression {};
struct list_close : one<']'> {};
struct list_unit : seq<sep, unit> {};
struct value_list : if_must<list_open, sep, list_item, star<sep, one<','>, sep, must<list_item>>, sep, list_close, opt<list_unit>> {};
struct range_dots : seq<sep, two<'.'>> {};
struct range_end : expression {};
struct range_step_keyword : kw_step {};
struct range_step : expression {};
struct range_tail : if_must<range_dots, sep, range_end, sep, range_step_keyword, sep, range_step> {};
struct single_value : success {};
struct scalar_value : seq<expression, sor<range_tail, single_value>> {};
struct setting_string : string_literal {};
struct setting_value : sor<setting_string, value_list, scalar_value> {};
// `step` is a keyword (ranges, the step protocol) and also a data line's setting: a key where `=` follows.
struct setting_key : sor<name, seq<kw_step, at<sep, one<'='>>>> {};
struct setting_equals : one<'='> {};
struct setting : seq<setting_key, sep, must<setting_equals>, sep, must<setting_value>> {};
struct protocol_kind : identifier {};  // `step` is both a protocol and a keyword
struct setting_next : if_must<seq<sep, one<','>>, sep, setting> {};
// `history "drive.csv"`, the file without its key (as a data line writes it): its own message.
struct protocol_file_key : failure {};
struct protocol_bare_string : seq<at<one<'"'>>, must<protocol_file_key>> {};
// A setting where a protocol's kind was expected (`solver = fixed` on a line of its own, or a
// setting after another without ','): its own message.
struct protocol_setting_alone : failure {};
struct protocol_bare_setting : seq<at<one<'='>>, must<protocol_setting_alone>> {};
struct protocol_line : seq<protocol_kind, sep, sor<protocol_bare_string, protocol_bare_setting, must<setting>>, star<setting_next>> {};
struct output_file : string_literal {};
struct output_line : if_must<kw_output, sep, output_file> {};
struct directive_line : sor<output_line, protocol_line> {};
struct simulate_model : name {};
struct simulate_open : one<'{'> {};
struct simulate_close : one<'}'> {};
struct simulate_decl : if_must<kw_simulate, sep, opt<simulate_model, sep>, simulate_open, star<sep, directive_line>, sep, simulate_close> {};

struct fit_data_keyword : TAO_PEGTL_KEYWORD("data") {};
struct fit_data_file : string_literal {};
struct fit_data_line : if_must<fit_data_keyword, sep, fit_data_file, star<setting_next>> {};
struct fit_output_keyword : kw_output {};
struct fit_output_file : string_literal {};
struct fit_output_line : if_must<fit_output_keyword, sep, fit_output_file> {};
struct fit_settings_begin : success {};
struct fit_settings_line : seq<at<setting_key>, fit_settings_begin, must<setting>, star<setting_next>> {};
struct fit_line : sor<fit_data_line, fit_output_line, fit_settings_line> {};
struct fit_model : name {};
struct fit_open : one<'{'> {};
struct fit_close : one<'}'> {};
struct fit_decl : if_must<kw_fit, sep, opt<fit_model, sep>, fit_open, star<sep, fit_line>, sep, fit_close> {};

struct top_item : sor<import_decl, model_decl, simulate_decl, fit_decl> {};
struct file_end : eof {};
struct file : seq<sep, star<top_item, sep>, must<file_end>> {};

// A protocol setting given on the command line: `frequency = 1 Hz .. 51 Hz step 2 Hz`.
struct setting_end : eof {};
struct command_line_setting : seq<sep, must<setting>, sep, must<setting_end>> {};

// A data file given on the command line with a data line's settings:
// `sweep.txt, step = "Amplitude sweep", area = 314 mm^2`. The name runs to the first comma, or
// is in double quotes (a name holding a comma).
struct command_line_data_name : plus<not_one<','>> {};
struct command_line_data_file : sor<seq<at<string_open>, fit_data_file>, command_line_data_name> {};
struct command_line_data_end : eof {};
struct command_line_data : seq<star<ascii::blank>, must<command_line_data_file>, star<setting_next>, sep, must<command_line_data_end>> {};

}  // namespace rheo::lang::grammar
