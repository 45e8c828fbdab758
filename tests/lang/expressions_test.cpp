#include "lang/expressions.hpp"

#include "lang/parser.hpp"

#include <doctest/doctest.h>

namespace expressions_test {

using namespace rheo::lang;

namespace {
// Compiles the value of `x = TEXT` with references k (stiffness, index 0) and t (time, index 1).
TypedExpression compile(const std::string& text, std::vector<Diagnostic>& errors) {
  static std::vector<ast::SettingNode> keep;
  keep.push_back(parse_setting_text("e", "x = " + text));
  Resolver r = [&](const ast::Expr& e) -> std::optional<ResolvedReference> {
    if (e.path == "k") return ResolvedReference{0, dim::stiffness};
    if (e.path == "t") return ResolvedReference{1, dim::time};
    errors.push_back({e.where, "unknown"});
    return std::nullopt;
  };
  return compile_expression(*keep.back().value.items.at(0), r, errors);
}
}  // namespace

TEST_CASE("compile_expression: unit literals convert to internal units") {
  std::vector<Diagnostic> errors;
  auto e = compile("4.335 ms", errors);
  CHECK(e.ok);
  CHECK_FALSE(e.free);
  CHECK(e.dimension == dim::time);
  CHECK(e.expression.evaluate({}) == doctest::Approx(4.335e-3).scale(0.0));
  CHECK(compile("2 kN/mm", errors).expression.evaluate({}) == 2000.0);
  CHECK(errors.empty());
}

TEST_CASE("compile_expression: free numbers adopt the other operand in + and -, are scalars in * and /") {
  std::vector<Diagnostic> errors;
  auto sum = compile("k + 5", errors);
  CHECK_FALSE(sum.free);
  CHECK(sum.dimension == dim::stiffness);
  CHECK(sum.expression.evaluate({10.0, 0.0}) == 15.0);
  auto product = compile("2 * k * t", errors);
  CHECK(product.dimension == dim::damping);
  CHECK(product.expression.evaluate({10.0, 0.5}) == 10.0);
  auto inverse = compile("1 / t", errors);
  CHECK(inverse.dimension == dim::frequency);
  auto free = compile("-(1 + 2) * 3", errors);
  CHECK(free.free);
  CHECK(free.expression.evaluate({}) == -9.0);
  CHECK(errors.empty());
}

TEST_CASE("compile_expression: mismatched + operands and unknown references are errors") {
  std::vector<Diagnostic> errors;
  auto bad = compile("k - 1 ms", errors);
  CHECK_FALSE(bad.ok);
  REQUIRE(errors.size() == 1);
  CHECK(errors[0].message.find("cannot subtract a stiffness (N/mm) and a time (s)") != std::string::npos);
  CHECK(errors[0].where.column == 7);
  errors.clear();
  CHECK_FALSE(compile("q * 2", errors).ok);
  CHECK(errors.size() == 1);
}

TEST_CASE("literal_unit: the unit written on a (negated) literal") {
  auto node = parse_setting_text("e", "x = -3 N/mm");
  CHECK(literal_unit(*node.value.items.at(0)) == "N/mm");
  auto sum = parse_setting_text("e", "x = 3 N/mm + 1 N/mm");
  CHECK(literal_unit(*sum.value.items.at(0)).empty());
}

}  // namespace expressions_test
