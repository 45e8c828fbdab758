#include "lang/stdlib.hpp"

#include "lang/frontend.hpp"

#include <doctest/doctest.h>

using namespace rheo::lang;

TEST_CASE("stdlib: the documented modules are embedded") {
  const std::vector<std::string> expected{"frictional_zener", "kelvin_voigt", "maxwell3", "series_friction_maxwell", "viscoplastic", "zener"};
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
