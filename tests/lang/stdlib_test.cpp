#include "lang/stdlib.hpp"

#include "lang/frontend.hpp"

#include <doctest/doctest.h>

namespace stdlib_test {

using namespace rheo::lang;

TEST_CASE("stdlib: the documented modules are embedded") {
  const std::vector<std::string> expected{"fractional_zener",
                                          "frictional_solid3",
                                          "frictional_zener",
                                          "hydromount",
                                          "hydromount_uncapped",
                                          "kelvin_voigt",
                                          "maxwell2",
                                          "maxwell3",
                                          "nonlinear_series_friction_maxwell",
                                          "nonlinear_viscoplastic",
                                          "series_friction_maxwell",
                                          "viscoplastic",
                                          "zener"};
  CHECK(stdlib_names() == expected);
  CHECK(stdlib_source("zener").value().find("model zener") != std::string_view::npos);
  CHECK_FALSE(stdlib_source("nope"));
  CHECK(stdlib_path("zener") == "<stdlib>/zener.rheo");
}

TEST_CASE("stdlib: every module compiles on import and defines the model of its name") {
  for (const auto& name : stdlib_names()) {
    CAPTURE(name);
    Program p = compile_source("t.rheo", "import " + name);
    REQUIRE(p.models.size() == 1);
    CHECK(p.models[0].name == name);
    CHECK(p.models[0].where.file == stdlib_path(name));
    CHECK(!p.models[0].root.children.empty());
  }
}

TEST_CASE("stdlib: series_friction_maxwell is a slider in series with a Maxwell arm, beside a spring") {
  Program p = compile_source("t.rheo", "import series_friction_maxwell");
  const auto& root = p.models.at(0).root;
  REQUIRE(root.children.size() == 2);
  CHECK(root.children[0].kind == ElementKind::spring);
  CHECK(root.children[1].kind == ElementKind::series);
  REQUIRE(root.children[1].children.size() == 2);
  CHECK(root.children[1].children[0].kind == ElementKind::slider);
  CHECK(root.children[1].children[1].kind == ElementKind::maxwell);
}

namespace {
// The kinds of an element's children, in order.
std::vector<ElementKind> kinds(const Element& e) {
  std::vector<ElementKind> out;
  for (const auto& c : e.children) out.push_back(c.kind);
  return out;
}
double value(const CheckedModel& m, const std::string& path) {
  for (const auto& p : m.parameters)
    if (p.path == path) return p.value;
  FAIL("no parameter " << path);
  return 0.0;
}
}  // namespace

TEST_CASE("stdlib: maxwell2 and frictional_solid3 are a spring beside two Maxwell arms / three friction elements") {
  using K = ElementKind;
  Program g = compile_source("t.rheo", "import maxwell2");
  CHECK(kinds(g.models.at(0).root) == std::vector<K>{K::spring, K::maxwell, K::maxwell});
  CHECK(value(g.models[0], "arm2.c") == doctest::Approx(30.0 * 0.020).scale(0.0));  // c = k tau, N*s/mm
  Program f = compile_source("t.rheo", "import frictional_solid3");
  CHECK(kinds(f.models.at(0).root) == std::vector<K>{K::spring, K::friction, K::friction, K::friction});
  CHECK(value(f.models[0], "f3.fy") == doctest::Approx(100.0 * 0.150));  // fy = kp uy, N
}

TEST_CASE("stdlib: the Fig. 2.6 and Fig. 9.1 models have a Yeoh spring where their linear versions have a spring") {
  using K = ElementKind;
  Program v = compile_source("t.rheo", "import nonlinear_viscoplastic");
  CHECK(kinds(v.models.at(0).root) == std::vector<K>{K::yeoh, K::maxwell, K::friction});
  CHECK(value(v.models[0], "elastic.D20") == doctest::Approx(-0.25).scale(0.0));
  Program s = compile_source("t.rheo", "import nonlinear_series_friction_maxwell");
  const auto& root = s.models.at(0).root;
  CHECK(kinds(root) == std::vector<K>{K::yeoh, K::series});
  CHECK(kinds(root.children.at(1)) == std::vector<K>{K::slider, K::maxwell});
}

TEST_CASE("stdlib: hydromount is a rubber spring beside a slider, a spring and the fluid node, the uncapped one lacks the slider") {
  using K = ElementKind;
  Program p = compile_source("t.rheo", "import hydromount");
  const CheckedModel& m = p.models.at(0);
  REQUIRE(kinds(m.root) == std::vector<K>{K::spring, K::series});
  const Element& fluid = m.root.children[1];
  REQUIRE(kinds(fluid) == std::vector<K>{K::slider, K::spring, K::parallel});
  CHECK(kinds(fluid.children[2]) == std::vector<K>{K::inerter, K::dashpot, K::spring});
  // Defaults of examples/hydrobushing.rheo's fluid branch; b = 40 kg = 0.04 N*s^2/mm.
  CHECK(value(m, "fluid.y.column.b") == doctest::Approx(0.040).scale(0.0));
  CHECK(value(m, "fluid.cap.fy") == doctest::Approx(60.0));
  CHECK(value(m, "fluid.chamber.k") == doctest::Approx(600.0));
  CHECK(value(m, "fluid.y.channel.c") == doctest::Approx(3.0));
  CHECK(value(m, "fluid.y.bulge.k") == doctest::Approx(150.0));
  CHECK(value(m, "rubber.k") == doctest::Approx(800.0));

  Program u = compile_source("t.rheo", "import hydromount_uncapped\nmodel w { hydromount_uncapped h (b = 20 kg) }");
  const CheckedModel* w = u.find_model("w");
  REQUIRE(w);
  REQUIRE(kinds(w->root.children.at(0)) == std::vector<K>{K::spring, K::series});
  const Element& ufluid = w->root.children[0].children[1];
  REQUIRE(kinds(ufluid) == std::vector<K>{K::spring, K::parallel});
  CHECK(kinds(ufluid.children[1]) == std::vector<K>{K::inerter, K::dashpot, K::spring});
  CHECK(value(*w, "h.fluid.y.column.b") == doctest::Approx(0.020).scale(0.0));  // the override reaches the inerter
}

}  // namespace stdlib_test
