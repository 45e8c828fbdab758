// A table's lines one at a time: what is passed over, the names and units rows, data rows with
// their rows and cell columns, a row too wide, and no header or no data.
#include "runtime/io/table_rows.hpp"

#include "runtime/core/errors.hpp"

#include <doctest/doctest.h>

#include <cmath>

namespace table_rows_test {

using namespace rheo::runtime;

TEST_CASE("lines that are blank or comments are passed over, the rest are names, units and data") {
  CHECK(TableRows::skips(""));
  CHECK(TableRows::skips(" \t\r"));
  CHECK(TableRows::skips("  # note"));
  CHECK_FALSE(TableRows::skips("\r\r"));  // one CR is the line end's, the other is text
  CHECK_FALSE(TableRows::skips("0,1"));
  Table table;
  table.path = "t.csv";
  TableLayout layout;
  TableRows rows(table, layout);
  CHECK_THROWS_WITH_AS(rows.finish(0), doctest::Contains("t.csv:1:1: error: no header found"), DataError);
  rows.line("# rig", 1);
  rows.line("time,displacement\r", 2);
  rows.line("ms,um", 3);
  CHECK_THROWS_WITH_AS(rows.finish(0), doctest::Contains("t.csv:2:1: error: the table has a header but no data rows"), DataError);
  rows.line("1.5, 250", 4);
  rows.line("", 5);
  rows.line("2,x", 6);
  CHECK(table.units_row == 3);
  CHECK(table.rows == std::vector<int>{4, 6});
  CHECK(table.columns[0] == std::vector<double>{1.5e-3, 2e-3});
  CHECK(table.columns[1][0] == doctest::Approx(0.25).scale(0.0));
  CHECK(std::isnan(table.columns[1][1]));
  CHECK(table.problems[1].rfind("t.csv:6:3: error: 'x' is not a number (column 'displacement')", 0) == 0);
  CHECK(table.cell_column(0, 1) == 5);
  CHECK_THROWS_WITH_AS(rows.line("3,4,5", 7), doctest::Contains("t.csv:7:5: error: this row has 3 values, the header has 2 columns"), DataError);
  rows.finish(2);
}

}  // namespace table_rows_test
