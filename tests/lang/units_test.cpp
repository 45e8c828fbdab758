#include "lang/units.hpp"

#include <doctest/doctest.h>

using namespace rheo::lang;

TEST_CASE("parse_unit: compound units and scales") {
  auto u = parse_unit("N*s/mm");
  REQUIRE(u);
  CHECK(u->dimension == dim::damping);
  CHECK(u->scale == 1.0);
  CHECK(parse_unit("kN/mm")->scale == 1000.0);
  CHECK(parse_unit("N/mm^5")->dimension == Dimension{1, -5, 0});
  CHECK(parse_unit("um")->scale == doctest::Approx(1e-3));
  CHECK(parse_unit("N/m")->scale == doctest::Approx(1e-3));
  CHECK_FALSE(parse_unit("N s/mm"));
  CHECK_FALSE(parse_unit("furlong"));
}

TEST_CASE("describe and internal_unit") {
  CHECK(describe(dim::stiffness) == "stiffness (N/mm)");
  CHECK(describe(dim::frequency) == "frequency (1/s)");
  CHECK(internal_unit(dim::damping) == "N*s/mm");
  CHECK(internal_unit(dim::none).empty());
}
