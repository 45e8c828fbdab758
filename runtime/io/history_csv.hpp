// Reading measured/derived tables: CSV with '#' comment lines, a header whose column names
// carry their unit in brackets ("time [s]", "displacement [um]", "force [kN]"), then numbers.
// Values are converted to the internal system (N, mm, s). A UTF-8 byte-order mark and CRLF line
// ends are accepted. Anything malformed (bytes that are not UTF-8 text, a NUL byte, no header,
// no data rows, a cell that is not a finite number, ...) is a DataError naming file:row:column
// and what to do; nothing is guessed. Cells are quoted in messages as printable text.
#pragma once

#include "lang/model.hpp"
#include "runtime/core/drive.hpp"

#include <string>
#include <vector>

namespace rheo::runtime {

struct Table {
  std::string path;
  int header_row = 0;                        // 1-based file line of the header
  std::vector<std::string> names;            // "time", "displacement", ...
  std::vector<std::string> units;            // as written: "s", "mm"
  std::vector<std::vector<double>> columns;  // internal units, column-major
  std::vector<int> rows;                     // 1-based file line of each data row
  std::vector<int> cell_columns;             // 1-based byte column of each cell, row-major

  int column(const std::string& name) const;  // -1 when absent
  // Byte column (1-based) of field `field` in data row `row_index` (0-based), for file:row:col.
  int cell_column(std::size_t row_index, int field) const;
};

// "file:row:1: error: " at the header, for a message about the table's columns or kind.
std::string header_error(const Table& table);
// "the header has: time, force", printable.
std::string header_columns(const Table& table);

// NAMED_AT, when given, is where a .rheo file names PATH: a file that cannot be read is then
// reported there (file:line:col of the name), since that is where to fix it.
Table read_table(const std::string& path, const lang::SourceLocation* named_at = nullptr);
Table parse_table(const std::string& path, const std::string& text);

// A displacement history from a table with "time" and "displacement" columns: strictly
// increasing time, starting from rest (displacement 0 at the first row). Time is shifted so
// that the drive starts at t = 0.
Drive drive_from_table(const Table& table);

}  // namespace rheo::runtime
