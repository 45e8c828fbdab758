// Raw syntax tree produced by the parser (parser.hpp): exactly what was written, with source
// locations, no name resolution, no units applied. The checker (checker.hpp) turns it into a
// Program (model.hpp).
#pragma once

#include "lang/model.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace rheo::lang::ast {

struct Expr;
using ExprPtr = std::unique_ptr<Expr>;

// number [unit] | reference path | -operand | lhs op rhs.
// A reference of one identifier is also how bare identifiers (`thesis`) are written.
struct Expr {
  enum class Kind { number, reference, negate, add, subtract, multiply, divide };
  Kind kind = Kind::number;
  double number = 0.0;  // Kind::number, as written (no unit applied)
  std::string unit;     // Kind::number: unit text directly after the literal, may be empty
  std::string path;     // Kind::reference: "m1.k"
  ExprPtr lhs, rhs;     // operands (negate uses lhs)
  SourceLocation where;
  int depth = 1;  // levels as written, parentheses included (limits.hpp)
};

struct Bounds {
  ExprPtr lower, upper;
  SourceLocation where;  // of the `in` keyword
};

// NAME = EXPR [in [LO, HI]], NAME may be a path for instantiation overrides (`m1.tau`).
struct Argument {
  std::string name;
  ExprPtr value;
  std::optional<Bounds> bounds;
  SourceLocation where;        // of the name
  SourceLocation value_where;  // of the value's first character
  int value_begin = -1;        // byte range [value_begin, value_end) of the value in the source text
  int value_end = -1;
};

// KIND [NAME] (ARGS)  or  parallel|series [NAME] { CHILDREN }
struct Element {
  bool block = false;  // parallel/series block
  std::string kind;    // "maxwell", "parallel", or a model name
  std::string name;    // empty when unnamed
  std::vector<Argument> arguments;
  std::vector<Element> children;
  SourceLocation where;       // of the kind word
  SourceLocation name_where;  // of the name, when given
};

struct Model {
  std::string name;
  std::vector<Argument> parameters;  // `param` declarations
  std::vector<Element> elements;
  SourceLocation where;  // of the name
};

struct Import {
  std::string name;
  SourceLocation where;  // of the name
};

// [a, b, c] [unit]   or   from .. to step by
struct SettingValue {
  enum class Kind { expression, list, range, string };
  Kind kind = Kind::expression;
  std::vector<ExprPtr> items;  // expression: 1; list: n; range: {from, to, step}
  std::string unit;            // list: trailing unit applying to unitless items
  std::string text;            // string literal contents
  SourceLocation where;
  int begin = -1;  // byte range [begin, end) of the value in the source text
  int end = -1;
};

struct SettingNode {
  std::string key;
  SettingValue value;
  SourceLocation where;
};

struct DirectiveLine {
  bool output = false;  // `output "FILE"` line
  std::string kind;     // protocol name
  std::string file;     // output file
  int file_begin = -1;  // byte offset of the file name's opening quote in the source text
  std::vector<SettingNode> settings;
  SourceLocation where;
};

struct Simulate {
  std::string model;  // empty when not named
  std::vector<DirectiveLine> lines;
  SourceLocation where;  // of the keyword
  SourceLocation model_where;
};

// A line of a fit block: `data "FILE" [, SETTING]*`, `output "FILE"` or `SETTING (, SETTING)*`.
struct FitLine {
  enum class Kind { data, output, settings };
  Kind kind = Kind::settings;
  std::string file;  // data, output
  std::vector<SettingNode> settings;
  SourceLocation where;       // of the first word
  SourceLocation file_where;  // of the file name
  int file_begin = -1;        // byte offset of the file name's opening quote in the source text
  int end = -1;               // data: byte offset just past the line's last setting (or its file name)
};

struct Fit {
  std::string model;  // empty when not named
  std::vector<FitLine> lines;
  SourceLocation where;  // of the keyword
  SourceLocation model_where;
};

struct File {
  std::string name;
  std::vector<Import> imports;
  std::vector<Model> models;
  std::vector<Simulate> simulations;
  std::vector<Fit> fits;
};

}  // namespace rheo::lang::ast
