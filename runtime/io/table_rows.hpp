// Reads a table's lines one at a time into a Table (history_csv.hpp): '#' comments and blank
// lines skipped, the names row (units in brackets or parentheses), a units row under it when
// the layout says so or it looks like one, then data rows converted to internal units. The
// whole-file reader (parse_table) and the streamed one (history_stream.hpp) share it, so that
// both read every cell alike and report the same faults at the same file:row:column.
#pragma once

#include "runtime/io/history_csv.hpp"
#include "runtime/io/table_layout.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace rheo::runtime {

class TableRows {
 public:
  // TABLE (its path set) receives the rows; both must outlive this reader.
  TableRows(Table& table, const TableLayout& layout) : t_(table), layout_(layout) {}

  // Line ROW (1-based) of the file, without its '\n'. A data row appends a value per column to
  // table.columns (NaN where a cell is not a finite number, its column's first problem noted in
  // table.problems), its row to table.rows and its cells' columns to table.cell_columns. A row
  // with more values than names is a DataError. No allocation once the vectors have grown.
  void line(std::string_view line, int row);
  // Whether line() passes LINE over: blank (spaces and tabs, after one '\r' at its end is
  // dropped) or a '#' comment.
  static bool skips(std::string_view line);
  // After the last line: a DataError when the table has no names row or no data rows.
  // DATA_ROWS counts the data rows read, including those a streamed reader has taken away.
  void finish(std::size_t data_rows) const;

 private:
  void names(int row);
  bool units(int row);
  void data(int row);
  double missing(std::size_t c, int row, const std::string& message, int column = 1);
  double value(std::string_view cell, std::size_t c, int row, int column);

  Table& t_;
  const TableLayout& layout_;
  bool units_in_names_ = false;
  bool under_names_ = false;
  std::vector<Cell> cells_;
  std::string scratch_;
};

}  // namespace rheo::runtime
