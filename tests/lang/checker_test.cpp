#include "lang/checker.hpp"

#include "lang/parser.hpp"

#include <doctest/doctest.h>

namespace checker_test {

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

namespace {
std::vector<Diagnostic> errors_of(const std::string& text) {
  std::vector<Diagnostic> errors;
  check(parse("m.rheo", text), {}, errors);
  return errors;
}
}  // namespace

TEST_CASE("check: long instantiation chains are checked without recursion, within the nesting limit") {
  std::string chain = "model m0 { spring s (k = 1 N/mm) }\n";
  for (int i = 1; i < 10000; ++i) chain += "model m" + std::to_string(i) + " { m" + std::to_string(i - 1) + " x () }\n";
  // m200 nests 200 instance blocks; instantiating it deepens that to 201, past max_block_depth.
  const auto errors = errors_of(chain);
  REQUIRE(errors.size() == 1);
  CHECK(errors[0].where.line == 202);
  CHECK(errors[0].message.find("instantiating model 'm200' here nests blocks 201 levels deep, more than 200") == 0);

  std::string cycle;
  for (int i = 0; i < 10000; ++i) cycle += "model m" + std::to_string(i) + " { m" + std::to_string((i + 1) % 10000) + " x () }\n";
  const auto recursion = errors_of(cycle);
  REQUIRE(recursion.size() == 1);
  CHECK(recursion[0].where.line == 10000);
  CHECK(recursion[0].message.find("recursive instantiation: m0 -> m1 -> m2") == 0);
  CHECK(recursion[0].message.find("m14 -> ... (9971 more) -> m9986") != std::string::npos);
}

TEST_CASE("check: a model that instantiates a failed model is not usable either") {
  std::vector<Diagnostic> errors;
  Program p = check(parse("m.rheo", "model bad { spring s (k = 1 mm) }\nmodel user { bad b () spring t (k = 1 in [0.5, 2]) }\nfit user { }\n"), {},
                    errors);
  REQUIRE(errors.size() == 1);  // only the bad spring: the fit block of `user` is not checked against a partial model
  CHECK(errors[0].message.find("expects a stiffness") != std::string::npos);
}

TEST_CASE("check: an unknown element's message lists the kinds and models it could name, not its own model") {
  const auto errors = errors_of("model bushing { sprng s (k = 1 N/mm) }\nmodel other { spring s (k = 1 N/mm) }\n");
  REQUIRE(errors.size() == 1);
  const std::string& message = errors[0].message;
  CAPTURE(message);
  CHECK(message.find("did you mean 'spring'?") != std::string::npos);
  CHECK(message.find(", other (and parallel, series blocks)") != std::string::npos);
  CHECK(message.find("bushing") == std::string::npos);
}

TEST_CASE("check: a misspelt parameter is reported once, not again as a missing one") {
  const auto errors = errors_of("model m { maxwell m1 (k = 1 N/mm, tua = 5 ms)\n spring s (kk = 2 N/mm) }\n");
  REQUIRE(errors.size() == 2);
  CHECK(errors[0].message.find("unknown parameter 'tua' for maxwell 'm1'; did you mean 'tau'?") != std::string::npos);
  CHECK(errors[1].message.find("unknown parameter 'kk' for spring 's'; did you mean 'k'?") != std::string::npos);
}

}  // namespace checker_test
