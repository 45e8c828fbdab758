// Table reading: units converted, every malformed input named by file:row:column.
#include "runtime/history_csv.hpp"

#include "runtime/errors.hpp"

#include <doctest/doctest.h>

#include <string>

using namespace rheo::runtime;

namespace {
std::string error_of(const std::string& text) {
  try {
    parse_table("t.csv", text);
  } catch (const DataError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("units in the header convert to N, mm, s; comments, BOM and CRLF are accepted") {
  const Table t = parse_table("t.csv", "\xEF\xBB\xBF# a comment\r\ntime [ms],displacement [um],force [kN]\r\n0,0,0\r\n10,500,1.5\r\n");
  REQUIRE(t.rows.size() == 2);
  CHECK(t.columns[0][1] == doctest::Approx(0.01));
  CHECK(t.columns[1][1] == doctest::Approx(0.5));
  CHECK(t.columns[2][1] == doctest::Approx(1500.0));
  CHECK(t.rows[1] == 4);
}

TEST_CASE("malformed tables are errors that name file:row:column") {
  CHECK(error_of("time [s],displacement [furlong]\n0,0\n").find("t.csv:1:") == 0);
  CHECK(error_of("time [s],displacement [furlong]\n0,0\n").find("unknown unit 'furlong'") != std::string::npos);
  CHECK(error_of("time [s],displacement\n0,0\n").find("has no unit") != std::string::npos);
  CHECK(error_of("time [s],displacement [mm]\n0,0\n1,abc\n").find("t.csv:3:3: error: 'abc' is not a number") == 0);
  CHECK(error_of("time [s],displacement [mm]\n0,0\n1,nan\n").find("t.csv:3:3: error: 'nan' is not a finite number") == 0);
  CHECK(error_of("time [s],displacement [mm]\n0,0\n1\n").find("t.csv:3:1: error: this row has 1 values") == 0);
  CHECK(error_of("").find("no header") != std::string::npos);
  CHECK(error_of("time [s],displacement [mm]\n").find("no data rows") != std::string::npos);
  CHECK(error_of(std::string("time [s]\n0\0", 11)).find("NUL") != std::string::npos);
}

TEST_CASE("a drive needs time and displacement, increasing time, and a start from rest") {
  auto drive_error = [](const std::string& text) {
    try {
      drive_from_table(parse_table("h.csv", text));
    } catch (const DataError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(drive_error("time [s],force [N]\n0,0\n1,1\n").find("needs columns 'time [s]' and 'displacement [mm]'") != std::string::npos);
  CHECK(drive_error("time [s],displacement [mm]\n0,0\n1,1\n1,2\n").find("h.csv:4:1: error: time must increase strictly") == 0);
  CHECK(drive_error("time [s],displacement [mm]\n0,0.5\n1,1\n").find("must start from rest") != std::string::npos);
  const Drive d = drive_from_table(parse_table("h.csv", "time [s],displacement [mm]\n2,0\n3,1\n"));
  CHECK(d.time[0] == 0.0);
  CHECK(d.time[1] == 1.0);
}
