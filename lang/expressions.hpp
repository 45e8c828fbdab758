// Expression AST -> postfix Expression with dimension inference.
//
// A number without a unit is "free": it has no dimension of its own. In + and - it adopts the
// other operand's dimension; in * and / it is a plain scalar; at the top the caller gives it
// the expected dimension. Its value is taken in the internal unit of that dimension (N, mm, s).
#pragma once

#include "lang/ast.hpp"
#include "lang/diagnostics.hpp"

#include <functional>
#include <optional>
#include <vector>

namespace rheo::lang {

struct TypedExpression {
  Expression expression;
  Dimension dimension;  // meaningless when free
  bool free = false;    // no unit anywhere that fixes the dimension
  bool ok = true;       // false when an error was reported
};

struct ResolvedReference {
  int index = -1;  // into the parameter list the Expression indexes
  Dimension dimension;
};

// Resolves a reference node; reports its own error and returns nullopt when it cannot.
using Resolver = std::function<std::optional<ResolvedReference>(const ast::Expr& reference)>;

TypedExpression compile_expression(const ast::Expr& e, const Resolver& resolve, std::vector<Diagnostic>& errors);

// The unit text written on a literal value (`-300 N/mm` -> "N/mm"); "" for anything else.
std::string literal_unit(const ast::Expr& e);

}  // namespace rheo::lang
