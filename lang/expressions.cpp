#include "lang/expressions.hpp"

#include "lang/names.hpp"

#include <fmt/format.h>

namespace rheo::lang {
namespace {

using Op = Expression::Op;
using Kind = ast::Expr::Kind;

void append(Expression& to, const Expression& from) { to.code.insert(to.code.end(), from.code.begin(), from.code.end()); }

TypedExpression combine(const ast::Expr& e, TypedExpression lhs, TypedExpression rhs, std::vector<Diagnostic>& errors) {
  TypedExpression out;
  out.ok = lhs.ok && rhs.ok;
  append(out.expression, lhs.expression);
  append(out.expression, rhs.expression);
  Op op = e.kind == Kind::add ? Op::add : e.kind == Kind::subtract ? Op::subtract : e.kind == Kind::multiply ? Op::multiply : Op::divide;
  out.expression.code.push_back({op});
  if (op == Op::add || op == Op::subtract) {
    // Free operands adopt the other side's dimension.
    out.free = lhs.free && rhs.free;
    out.dimension = lhs.free ? rhs.dimension : lhs.dimension;
    if (!lhs.free && !rhs.free && lhs.dimension != rhs.dimension && out.ok) {
      errors.push_back({e.where, fmt::format("cannot {} {} and {}; both operands of '{}' need the same dimension", op == Op::add ? "add" : "subtract",
                                             with_article(lhs.dimension), with_article(rhs.dimension), op == Op::add ? '+' : '-')});
      out.ok = false;
    }
    return out;
  }
  // Free operands are scalars in products.
  out.free = lhs.free && rhs.free;
  Dimension l = lhs.free ? dim::none : lhs.dimension;
  Dimension r = rhs.free ? dim::none : rhs.dimension;
  out.dimension = op == Op::multiply ? l * r : l / r;
  return out;
}

}  // namespace

TypedExpression compile_expression(const ast::Expr& e, const Resolver& resolve, std::vector<Diagnostic>& errors) {
  TypedExpression out;
  switch (e.kind) {
    case Kind::number: {
      double scale = 1.0;
      out.free = e.unit.empty();
      if (!out.free) {
        auto unit = parse_unit(e.unit);
        if (!unit) {
          errors.push_back({e.where, fmt::format("unknown unit '{}'; write units like N/mm, N*s/mm or N/mm^3", e.unit)});
          out.ok = false;
        } else {
          out.dimension = unit->dimension;
          scale = unit->scale;
        }
      }
      out.expression.code.push_back({Op::constant, e.number * scale});
      return out;
    }
    case Kind::reference: {
      auto r = resolve(e);
      if (!r) {
        out.ok = false;
        out.expression.code.push_back({Op::constant, 0.0});
        return out;
      }
      out.dimension = r->dimension;
      out.expression.code.push_back({Op::parameter, 0.0, r->index});
      return out;
    }
    case Kind::negate:
      out = compile_expression(*e.lhs, resolve, errors);
      out.expression.code.push_back({Op::negate});
      return out;
    default: return combine(e, compile_expression(*e.lhs, resolve, errors), compile_expression(*e.rhs, resolve, errors), errors);
  }
}

std::string literal_unit(const ast::Expr& e) {
  if (e.kind == Kind::negate) return literal_unit(*e.lhs);
  return e.kind == Kind::number ? e.unit : std::string();
}

}  // namespace rheo::lang
