#include "lang/model.hpp"

#include <doctest/doctest.h>

#include <cmath>

namespace model_test {

using namespace rheo::lang;
using Op = Expression::Op;

TEST_CASE("Expression::evaluate runs postfix code over parameter values") {
  // (p0 - 2) * -p1 / 4
  Expression e{
      {{Op::parameter, 0, 0}, {Op::constant, 2.0}, {Op::subtract}, {Op::parameter, 0, 1}, {Op::negate}, {Op::multiply}, {Op::constant, 4.0}, {Op::divide}}};
  CHECK(e.evaluate({10.0, 3.0}) == doctest::Approx(-6.0));
  CHECK_FALSE(e.is_constant());
  Expression c{{{Op::constant, 1.0}, {Op::constant, 0.0}, {Op::divide}}};
  CHECK(c.is_constant());
  CHECK(std::isinf(c.evaluate({})));
  Expression sum{{{Op::constant, 1.5}, {Op::constant, 2.0}, {Op::add}}};
  CHECK(sum.evaluate({}) == 3.5);
}

TEST_CASE("Program::find_model looks up by name") {
  Program prog;
  prog.models.emplace_back().name = std::string("a");  // not a literal: GCC 12 -Wrestrict misfires (bug 105329)
  CHECK(prog.find_model("a") == &prog.models[0]);
  CHECK(prog.find_model("b") == nullptr);
}

}  // namespace model_test
