#include "lang/protocol_schema.hpp"

#include "lang/parser.hpp"

#include <doctest/doctest.h>

namespace protocol_schema_test {

using namespace rheo::lang;

namespace {
std::optional<Setting> check(ProtocolKind kind, const std::string& text, std::vector<Diagnostic>& errors) {
  return check_setting(kind, parse_setting_text("s", text), errors);
}
}  // namespace

TEST_CASE("protocol names map to kinds") {
  CHECK(protocol_kind("static") == ProtocolKind::static_triangle);
  CHECK(protocol_kind("step") == ProtocolKind::step);
  CHECK_FALSE(protocol_kind("harmonc"));
  CHECK(protocol_name(ProtocolKind::quasistatic) == "quasistatic");
  CHECK(protocol_names().size() == 5);
}

TEST_CASE("check_setting: ranges include an end within 1e-9 relative, lists take a trailing unit") {
  std::vector<Diagnostic> errors;
  auto r = check(ProtocolKind::harmonic, "frequency = 0.1 Hz .. 0.3 Hz step 0.1 Hz", errors);
  REQUIRE(r);
  CHECK(r->values.size() == 3);
  CHECK(r->values.back() == 0.3);
  auto l = check(ProtocolKind::harmonic, "amplitude = [200, 0.5 mm] um", errors);
  REQUIRE(l);
  CHECK(l->values[0] == doctest::Approx(0.2).scale(0.0));
  CHECK(l->values[1] == doctest::Approx(0.5).scale(0.0));
  auto single = check(ProtocolKind::harmonic, "amplitude = 2", errors);  // plain: internal unit mm
  CHECK(single->values == std::vector<double>{2.0});
  auto count = check(ProtocolKind::harmonic, "steps_per_cycle = 64", errors);
  CHECK(count->values == std::vector<double>{64.0});
  auto file = check(ProtocolKind::history, "file = \"data/road.csv\"", errors);
  CHECK(file->text == "data/road.csv");
  CHECK(errors.empty());
}

TEST_CASE("check_setting: schema violations are reported") {
  std::vector<Diagnostic> errors;
  CHECK_FALSE(check(ProtocolKind::harmonic, "frequency = 1 Hz .. 5 Hz step -1 Hz", errors));
  CHECK_FALSE(check(ProtocolKind::harmonic, "steps_per_cycle = 18", errors));
  CHECK_FALSE(check(ProtocolKind::static_triangle, "velocity = 1 mm", errors));
  CHECK_FALSE(check(ProtocolKind::step, "elements = some", errors));
  CHECK_FALSE(check(ProtocolKind::step, "frequency = 1 Hz", errors));
  CHECK_FALSE(check(ProtocolKind::history, "file = k0", errors));
  REQUIRE(errors.size() == 6);
  CHECK(errors[0].message.find("step of a range must be positive") != std::string::npos);
  CHECK(errors[1].message.find("multiple of 4") != std::string::npos);
  CHECK(errors[2].message.find("velocity expects a velocity (mm/s), got a length (mm)") != std::string::npos);
  CHECK(errors[3].message.find("elements must be one of: all, none") != std::string::npos);
  CHECK(errors[4].message.find("unknown setting 'frequency' for step") != std::string::npos);
  CHECK(errors[5].message.find("file takes a file name in double quotes") != std::string::npos);
}

TEST_CASE("check_protocol: duplicates and missing required settings") {
  std::vector<Diagnostic> errors;
  std::vector<ast::SettingNode> nodes;
  nodes.push_back(parse_setting_text("s", "amplitude = 1 mm"));
  nodes.push_back(parse_setting_text("s", "amplitude = 2 mm"));
  Protocol p = check_protocol(ProtocolKind::harmonic, nodes, {"s", 1, 1}, errors);
  CHECK(p.written.size() == 1);
  CHECK(std::get<HarmonicSettings>(p.settings).amplitudes == std::vector<double>{1.0});  // the first given
  REQUIRE(errors.size() == 2);
  CHECK(errors[0].message.find("duplicate setting 'amplitude'") != std::string::npos);
  CHECK(errors[1].message.find("harmonic requires the setting 'frequency'") != std::string::npos);
}

TEST_CASE("a history's columns: time and displacement by name or HDF5 path, decoded: other roles and malformed pairs refused") {
  std::vector<Diagnostic> errors;
  const auto columns = check(ProtocolKind::history, "columns = \"time = /rig/t [ms], displacement = weg\"", errors);
  REQUIRE(columns);
  CHECK(errors.empty());
  const auto settings = decode_protocol_settings(ProtocolKind::history, {*columns});
  CHECK(std::get<HistorySettings>(settings).columns == std::vector<ColumnName>{{"time", "/rig/t [ms]"}, {"displacement", "weg"}});
  CHECK_FALSE(check(ProtocolKind::history, "columns = \"force = F\"", errors));
  REQUIRE(errors.size() == 1);
  CHECK(errors[0].message == "columns: 'force' is not a role rheo reads; use time, displacement");
  errors.clear();
  CHECK_FALSE(check(ProtocolKind::history, "columns = \"time\"", errors));
  REQUIRE(errors.size() == 1);
  CHECK(errors[0].message.find("columns takes 'role = column name' pairs separated by commas, e.g. columns = \"time = t, displacement = s\"") == 0);
  errors.clear();
  CHECK_FALSE(check(ProtocolKind::harmonic, "columns = \"time = t\"", errors));  // histories only
  CHECK(errors.size() == 1);
}

}  // namespace protocol_schema_test
