#include "lang/names.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

namespace names_test {

using namespace rheo::lang;

TEST_CASE("closest suggests only plausible names") {
  CHECK(closest("sprng", {"spring", "slider", "series"}) == "spring");
  CHECK(closest("xyzzy", {"spring", "slider"}).empty());
  CHECK(did_you_mean("tua", {"k", "tau", "c"}) == " did you mean 'tau'?");
  CHECK(join({"a", "b"}) == "a, b");
}

TEST_CASE("lists and chains in messages are cut past 30 names, suggestions only among a bounded set") {
  std::vector<std::string> many;
  for (int i = 0; i < 1000000; ++i) many.push_back(fmt::format("p{}", i));
  CHECK(join(many) ==
        "p0, p1, p2, p3, p4, p5, p6, p7, p8, p9, p10, p11, p12, p13, p14, p15, p16, p17, p18, p19, p20, p21, p22, "
        "p23, p24, p25, p26, p27, p28, p29, ... (999970 more)");
  CHECK(join_chain({"a", "b", "a"}) == "a -> b -> a");
  const std::vector<std::string> chain(many.begin(), many.begin() + 40);
  CHECK(join_chain(chain) ==
        "p0 -> p1 -> p2 -> p3 -> p4 -> p5 -> p6 -> p7 -> p8 -> p9 -> p10 -> p11 -> p12 -> p13 -> p14 -> ... (10 more) "
        "-> p25 -> p26 -> p27 -> p28 -> p29 -> p30 -> p31 -> p32 -> p33 -> p34 -> p35 -> p36 -> p37 -> p38 -> p39");
  const std::vector<std::string> bounded(many.begin(), many.begin() + static_cast<std::ptrdiff_t>(kMaxSuggestionCandidates));
  CHECK(closest("p99x", bounded) == "p99");
  CHECK(closest("p99x", many).empty());  // too many to search for every misspelt name
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

}  // namespace names_test
