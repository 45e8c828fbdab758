#include "lang/names.hpp"

#include <doctest/doctest.h>

using namespace rheo::lang;

TEST_CASE("closest suggests only plausible names") {
  CHECK(closest("sprng", {"spring", "slider", "series"}) == "spring");
  CHECK(closest("xyzzy", {"spring", "slider"}).empty());
  CHECK(did_you_mean("tua", {"k", "tau", "c"}) == " did you mean 'tau'?");
  CHECK(join({"a", "b"}) == "a, b");
}

TEST_CASE("with_article and show_value word dimensions and values") {
  CHECK(with_article(dim::stiffness) == "a stiffness (N/mm)");
  CHECK(with_article(dim::energy) == "an energy (N*mm)");
  CHECK(with_article(dim::none) == "a plain number");
  CHECK(with_article({1, -3, 0}) == "N/mm^3");
  CHECK(show_value(-3.0, dim::stiffness, "N/mm") == "-3 N/mm");
  CHECK(show_value(0.004335, dim::time, "ms") == "4.335 ms");
  CHECK(show_value(2.0, dim::damping, "") == "2 N*s/mm");
}
