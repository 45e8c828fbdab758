#include "lang/checker.hpp"

#include "lang/parser.hpp"

#include <doctest/doctest.h>

using namespace rheo::lang;

TEST_CASE("check: imported models are checked first and can be instantiated") {
  ast::File lib = parse("<stdlib>/lib.rheo", "model base { spring (k = 1) }");
  ast::File main = parse("m.rheo", "model top { base b () }\nsimulate { step amplitude = 1 mm, duration = 1 s }");
  std::vector<Diagnostic> errors;
  Program p = check(main, {&lib}, errors);
  CHECK(errors.empty());
  REQUIRE(p.models.size() == 2);
  CHECK(p.models[0].name == "base");
  CHECK(p.simulations.at(0).model == "top");
}

TEST_CASE("check: several errors across models and directives accumulate") {
  ast::File main = parse("m.rheo", "model a { spring (k = 1 mm) }\nmodel a { x () }\nsimulate { bogus x = 1 }");
  std::vector<Diagnostic> errors;
  check(main, {}, errors);
  REQUIRE(errors.size() == 4);
  CHECK(errors[0].message.find("duplicate model 'a'") != std::string::npos);
  CHECK(errors[1].message.find("expects a stiffness") != std::string::npos);
  CHECK(errors[2].message.find("this file defines several models") != std::string::npos);
  CHECK(errors[3].message.find("unknown protocol 'bogus'") != std::string::npos);
}
