// The FMU's variables: references in order, units, starts and bounds as the model states them,
// and the fingerprint that ties an FMU's description to its resources.
#include "runtime/fmu/fmu_variables.hpp"

#include "runtime/core/errors.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <limits>
#include <regex>

namespace fmu_variables_test {

using namespace rheo;
using runtime::fmu::Causality;

namespace {

const runtime::fmu::Variable& named(const std::vector<runtime::fmu::Variable>& vs, const std::string& name) {
  for (const auto& v : vs)
    if (v.name == name) return v;
  FAIL("no variable " << name);
  return vs.front();
}

}  // namespace

TEST_CASE("fmu variables: u, F and v first, then every parameter in the model's order, in internal units, then time") {
  const auto model = test::model_from(
      "model m {\n  maxwell m1 (k = 61.476 N/mm, tau = 4.335 ms)\n  friction f1 (k = 1 kN/mm in [0.1, 5], uy = 101.58 um)\n"
      "  springpot p (k = 10 N/mm, alpha = 0.3, tau = 1 s)\n  yeoh y (D10 = 300 N/mm, D20 = -2 N/mm^3, D30 = 0.1 N/mm^5)\n}",
      "m");
  const auto vs = runtime::fmu::fmu_variables(model);
  REQUIRE(vs.size() == 4 + model.parameters.size());
  for (std::size_t i = 0; i < vs.size(); ++i) CHECK(vs[i].reference == i);
  CHECK(vs[0].name == "u");
  CHECK(vs[0].causality == Causality::input);
  CHECK(vs[0].unit == "mm");
  CHECK(vs[1].name == "F");
  CHECK(vs[1].causality == Causality::output);
  CHECK(vs[1].unit == "N");
  CHECK(vs[2].name == "v");
  CHECK(vs[2].causality == Causality::input);
  CHECK(vs[2].unit == "mm/s");
  CHECK(vs[2].start == 0.0);
  for (std::size_t i = 0; i < model.parameters.size(); ++i) {
    CHECK(vs[i + 3].name == model.parameters[i].path);
    CHECK(vs[i + 3].start == model.parameters[i].value);
  }
  CHECK(vs.back().name == "time");
  CHECK(vs.back().causality == Causality::independent);
  CHECK(vs.back().unit == "s");
  CHECK(vs.back().parameter == -1);
  // Written units become internal ones: ms -> s, um -> mm, kN/mm -> N/mm.
  CHECK(named(vs, "m1.tau").unit == "s");
  CHECK(named(vs, "m1.tau").start == doctest::Approx(4.335e-3).epsilon(1e-15).scale(0.0));
  CHECK(named(vs, "f1.uy").unit == "mm");
  CHECK(named(vs, "f1.k").start == 1000.0);
  // A value computed from others (maxwell c = k tau, friction fy = k uy) is a calculatedParameter.
  CHECK(named(vs, "m1.c").causality == Causality::calculated_parameter);
  CHECK(named(vs, "m1.c").unit == "N*s/mm");
  CHECK(named(vs, "f1.fy").causality == Causality::calculated_parameter);
  CHECK(named(vs, "m1.k").causality == Causality::parameter);
  // Bounds: the fit's `in [lo, hi]`, else the law's own (> 0, alpha < 1), else none.
  CHECK(named(vs, "f1.k").min == 100.0);
  CHECK(named(vs, "f1.k").max == 5000.0);
  CHECK(named(vs, "m1.k").min == std::numeric_limits<double>::min());
  CHECK_FALSE(named(vs, "m1.k").max.has_value());
  CHECK(named(vs, "p.alpha").max == std::nextafter(1.0, 0.0));
  CHECK_FALSE(named(vs, "y.D20").min.has_value());
  CHECK_FALSE(named(vs, "y.D20").max.has_value());
  CHECK(named(vs, "y.D20").unit == "N/mm^3");
  CHECK(named(vs, "m1.k").description.find("stiffness of maxwell 'm1', line 2:") == 0);
}

TEST_CASE("fmu variables: a model-level parameter named u, F, v or time is refused, naming where it is written") {
  const auto model = test::model_from("model m {\n  param u = 3 N/mm\n  spring s (k = u)\n}", "m");
  CHECK_THROWS_WITH_AS(runtime::fmu::fmu_variables(model), doctest::Contains("test.rheo:2:"), ModelError);
  const auto timed = test::model_from("model m {\n  spring s (k = 1)\n  param time = 3 s\n  maxwell m1 (k = 1, tau = time)\n}", "m");
  CHECK_THROWS_WITH_AS(runtime::fmu::fmu_variables(timed),
                       doctest::Contains("test.rheo:3:16: error: parameter 'time' of model 'm' has the name of the FMU's independent variable time"),
                       ModelError);
}

TEST_CASE("fmu guid: a 128-bit fingerprint of version, model and source, each of which changes it") {
  const std::string g = runtime::fmu::fmu_guid("0.1.0", "m", "model m { spring s (k = 1) }");
  CHECK(std::regex_match(g, std::regex(R"(\{[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}\})")));
  CHECK(g == runtime::fmu::fmu_guid("0.1.0", "m", "model m { spring s (k = 1) }"));
  CHECK(g != runtime::fmu::fmu_guid("0.1.1", "m", "model m { spring s (k = 1) }"));
  CHECK(g != runtime::fmu::fmu_guid("0.1.0", "n", "model m { spring s (k = 1) }"));
  CHECK(g != runtime::fmu::fmu_guid("0.1.0", "m", "model m { spring s (k = 2) }"));
}

}  // namespace fmu_variables_test
