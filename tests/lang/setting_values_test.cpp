#include "lang/setting_values.hpp"

#include "lang/parser.hpp"

#include <doctest/doctest.h>

namespace setting_values_test {

using namespace rheo::lang;

namespace {
bool check(const SettingSpec& spec, const std::string& text, Setting& out, std::vector<Diagnostic>& errors, std::vector<PathItem>* paths = nullptr) {
  return check_setting_value(parse_setting_text("s", text), spec, out, errors, paths);
}
}  // namespace

TEST_CASE("check_setting_value: inclusive value ranges") {
  const SettingSpec weight{.key = "w", .shape = Shape::number, .dimension = dim::none, .lowest = 0.0, .highest = 1.0};
  std::vector<Diagnostic> errors;
  Setting out;
  CHECK(check(weight, "w = 0", out, errors));
  CHECK(check(weight, "w = 1", out, errors));
  CHECK(out.values == std::vector<double>{0.0, 1.0});
  CHECK_FALSE(check(weight, "w = 1.01", out, errors));
  REQUIRE(errors.size() == 1);
  CHECK(errors[0].message == "w must be between 0 and 1, got 1.01");
  const SettingSpec at_least{.key = "w", .shape = Shape::list, .dimension = dim::length, .lowest = 0.0};
  CHECK_FALSE(check(at_least, "w = [1, -2] mm", out, errors));
  CHECK(errors.back().message == "w must be at least 0 mm, got -2 mm");
}

TEST_CASE("check_setting_value: parameter paths, one or a list") {
  const SettingSpec free{.key = "free", .shape = Shape::paths, .dimension = dim::none};
  std::vector<Diagnostic> errors;
  Setting out;
  std::vector<PathItem> paths;
  CHECK(check(free, "free = m1.k", out, errors, &paths));
  CHECK(check(free, "free = [rubber.D10, k0]", out, errors, &paths));
  REQUIRE(paths.size() == 3);
  CHECK(paths[0].path == "m1.k");
  CHECK(paths[2].path == "k0");
  CHECK(paths[2].where.column == 21);
  CHECK(errors.empty());
  CHECK_FALSE(check(free, "free = \"m1.k\"", out, errors, &paths));
  CHECK_FALSE(check(free, "free = [m1.k] mm", out, errors, &paths));
  CHECK_FALSE(check(free, "free = [m1.k, 2 * k0]", out, errors, &paths));
  REQUIRE(errors.size() == 3);
  CHECK(errors[0].message == "free takes a list of parameter paths, e.g. `free = [m1.k, m1.tau]`");
  CHECK(errors[2].where.column == 17);  // a binary expression is located at its operator
}

}  // namespace setting_values_test
