// Table reading: units converted, every malformed input named by file:row:column.
#include "runtime/io/history_csv.hpp"

#include "runtime/core/errors.hpp"

#include <doctest/doctest.h>

#include <string>

namespace history_csv_test {

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
std::string drive_error(const std::string& text) {
  try {
    drive_from_table(parse_table("h.csv", text));
  } catch (const DataError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("units in the header convert to N, mm, s, comments, BOM and CRLF are accepted") {
  const Table t = parse_table("t.csv", "\xEF\xBB\xBF# a comment\r\ntime [ms],displacement [um],force [kN]\r\n0,0,0\r\n10,500,1.5\r\n");
  REQUIRE(t.rows.size() == 2);
  CHECK(t.columns[0][1] == doctest::Approx(0.01).scale(0.0));
  CHECK(t.columns[1][1] == doctest::Approx(0.5).scale(0.0));
  CHECK(t.columns[2][1] == doctest::Approx(1500.0));
  CHECK(t.rows[1] == 4);
}

TEST_CASE("malformed tables are errors that name file:row:column") {
  CHECK(error_of("").find("no header") != std::string::npos);
  CHECK(error_of("time [s],displacement [mm]\n").find("no data rows") != std::string::npos);
  CHECK(error_of(std::string("time [s]\n0\0", 11)).find("NUL") != std::string::npos);
  // More values than names cannot be told apart from a shifted row, whichever columns are read.
  CHECK(error_of("time [s],displacement [mm]\n0,0\n1,2,3\n").find("t.csv:3:5: error: this row has 3 values, the header has 2 columns") == 0);
}

TEST_CASE("a column is checked when a reader uses it: its unit, its kind and every cell, at file:row:column") {
  CHECK(drive_error("time [s],displacement [furlong]\n0,0\n").find("h.csv:1:24: error: unknown unit 'furlong'") == 0);
  CHECK(drive_error("time [s],displacement\n0,0\n").find("h.csv:1:10: error: column 'displacement' has no unit; write it as") == 0);
  // A unit of the wrong dimension for the column read, at the unit's column.
  CHECK(drive_error("time [mm],displacement [mm]\n0,0\n")
            .find("h.csv:1:7: error: column 'time' has unit 'mm', a length (mm); time needs a unit of time (s), e.g. 'time [s]'") == 0);
  CHECK(drive_error("time [s],displacement [N/mm]\n0,0\n").find("column 'displacement' has unit 'N/mm', a stiffness (N/mm)") != std::string::npos);
  CHECK(drive_error("time [s],displacement [mm]\n0,0\n1,abc\n").find("h.csv:3:3: error: 'abc' is not a number") == 0);
  CHECK(drive_error("time [s],displacement [mm]\n0,0\n1,nan\n").find("h.csv:3:3: error: 'nan' is not a finite number") == 0);
  CHECK(drive_error("time [s],displacement [mm]\n0,0\n1\n").find("h.csv:3:1: error: this row has 1 values, the header has 2 columns") == 0);
  CHECK(drive_error("time [s],displacement [mm],x,y\n0,0,a,b\n1,0,,\n").empty());  // columns no reader uses are not checked
  CHECK(drive_error("time [s],displacement [mm],displacement [mm]\n0,0,0\n1,1,1\n")
            .find("h.csv:1:28: error: column 'displacement' appears twice in the header (columns 2 and 3)") == 0);
}

TEST_CASE("a drive needs time and displacement and increasing time, it starts where its first row is, or from rest where asked") {
  CHECK(drive_error("time [s],force [N]\n0,0\n1,1\n").find("needs columns 'time [s]' and 'displacement [mm]'") != std::string::npos);
  CHECK(drive_error("time [s],displacement [mm]\n0,0\n1,1\n1,2\n").find("h.csv:4:1: error: time must increase strictly") == 0);
  const Table moving = parse_table("h.csv", "time [s],displacement [mm]\n0,0.5\n1,1\n");
  CHECK(drive_from_table(moving).displacement.front() == 0.5);  // the relaxed start
  try {
    drive_from_table(moving, true);
    FAIL("start = rest accepted a history from 0.5 mm");
  } catch (const rheo::runtime::DataError& e) {
    CHECK(std::string(e.what()).find("h.csv:2:3: error: with start = rest the history must start from rest") == 0);
  }
  const Drive d = drive_from_table(parse_table("h.csv", "time [s],displacement [mm]\n2,0\n3,1\n"));
  CHECK(d.time[0] == 0.0);
  CHECK(d.time[1] == 1.0);
}

TEST_CASE("text that is not UTF-8, NUL bytes and control characters: errors at row:col that quote nothing raw") {
  CHECK(error_of("time [s],displacement [mm]\n0,0\n0.1,0\xb7"
                 "5\n")
            .find("t.csv:3:6: error: found byte 0xB7, which is not UTF-8") == 0);
  CHECK(error_of(std::string("time [s],displacement [mm]\n0,0\n0.1,\0\n", 36)).find("t.csv:3:5: error: found a NUL byte") == 0);
  const std::string control = drive_error("time [s],displacement [mm]\n0,0\n0.1,\x1b[2J\n");
  CHECK(control.find("h.csv:3:5: error: '\xEF\xBF\xBD[2J' is not a number") == 0);
  CHECK(drive_error("time [s],displacement [mm]\n0,0\n0.1," + std::string(1000, '9') + "x\n").size() < 300);  // a long cell is cut
  CHECK(drive_error("time [s],displacement [mm]\n0,0\n0.1,1e999\n").find("h.csv:3:5: error: '1e999' is not a finite number") == 0);
}

TEST_CASE("an empty table, a header alone and a missing column are errors at a row and column") {
  CHECK(error_of("").find("t.csv:1:1: error: no header found") == 0);
  CHECK(error_of("# only\n# comments\n").find("t.csv:1:1: error: no header found") == 0);
  CHECK(error_of("# rig 2\ntime [s],displacement [mm]\n").find("t.csv:2:1: error: the table has a header but no data rows") == 0);
  const std::string drive = drive_error("# x\ntime [s],force [N]\n0,0\n1,1\n");
  CHECK(drive.find("h.csv:2:1: error: a displacement history needs columns 'time [s]' and 'displacement [mm]'") == 0);
  CHECK(drive.find("the header has: time, force") != std::string::npos);
}

TEST_CASE("a history's rows: at least two, time strictly increasing (no repeated row)") {
  CHECK(drive_error("time [s],displacement [mm]\n0,0\n").find("h.csv:2:1: error: a history needs at least two rows") == 0);
  CHECK(drive_error("time [s],displacement [mm]\n0,0\n0.1,0.5\n0.1,0.5\n")
            .find("h.csv:4:1: error: time must increase strictly (row 4 has 0.1 s after 0.1 s at row 3)") == 0);
  CHECK(drive_error("time [s],displacement [mm]\n0,0\n0.2,0.5\n0.1,0\n").find("h.csv:4:1: error: time must increase strictly") == 0);
}

TEST_CASE("read_table: a directory is not a table") {
  CHECK_THROWS_WITH_AS(read_table(RHEO_DATA_DIR), doctest::Contains("cannot read the file (it is a directory)"), DataError);
}

TEST_CASE("a table that almost matches says what rheo expected and what it found: another separator, units above the names, units in a data row") {
  const std::string piped = drive_error("time [s]|displacement [mm]\n0|0\n1|1\n");
  CHECK(piped.find("is '|' its separator?") != std::string::npos);
  CHECK(drive_error("time [s] displacement [mm]\n0 0\n1 1\n").find("is a space its separator?") != std::string::npos);
  const std::string above = drive_error("s,mm\ntime,displacement\n0,0\n1,1\n");
  CHECK(above.find("these look like units: put the names row first") != std::string::npos);
  CHECK(drive_error("time [s],force [N]\n0,0\n1,1\n").find("look like units") == std::string::npos);  // real names: no hint
  const std::string below = error_of("time,displacement\n0,0\ns,mm\n");
  CHECK(below.empty());  // a column is checked when a reader uses it
  const std::string used = drive_error("time,displacement\n0,0\ns,mm\n");
  CHECK(used.find("'s' reads as a unit: units go in the names row") != std::string::npos);
}

}  // namespace history_csv_test
