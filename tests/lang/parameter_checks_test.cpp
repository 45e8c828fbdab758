#include "lang/parameter_checks.hpp"

#include "lang/parser.hpp"

#include <doctest/doctest.h>

namespace parameter_checks_test {

using namespace rheo::lang;

TEST_CASE("describe_parameter: element parameters by owner, model parameters by name") {
  Parameter p;
  p.path = "fluid.m1.tau";
  CHECK(describe_parameter(p, {true, false, "time constant", "maxwell"}) == "tau of maxwell 'fluid.m1'");
  p.path = "k0";
  CHECK(describe_parameter(p, {}) == "parameter 'k0'");
}

TEST_CASE("check_bounds: plain bounds take the value's unit, the parameter becomes free") {
  ast::File f = parse("b.rheo", "model m { param k0 = 5 um in [1, 10] }");
  const ast::Bounds& b = *f.models.at(0).parameters.at(0).bounds;
  Parameter p;
  p.path = "k0";
  p.dimension = dim::length;
  p.unit = std::string{"um"};
  p.value = 5e-3;
  p.expression.code = {{Expression::Op::constant, 5e-3}};
  std::vector<Diagnostic> errors;
  CHECK(check_value(p, {}, errors));
  CHECK(check_bounds(p, {}, b, errors));
  CHECK(errors.empty());
  CHECK(p.free);
  CHECK(p.lower == doctest::Approx(1e-3).scale(0.0));
  CHECK(p.upper == doctest::Approx(1e-2).scale(0.0));
  p.value = 0.1;
  CHECK_FALSE(check_bounds(p, {}, b, errors));
  REQUIRE(errors.size() == 1);
  CHECK(errors[0].message == "parameter 'k0' = 100 um lies outside its bounds [1 um, 10 um]");
}

}  // namespace parameter_checks_test
