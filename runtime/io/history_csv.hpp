// Reading measured/derived tables (layout: table_layout.hpp): a names row whose names carry their
// unit in brackets or parentheses ("time [s]", "Storage modulus (MPa)") or a units row under it
// ("f, E_stor" then "Hz, MPa"), then rows of numbers. Values are converted to the internal system
// (N, mm, s). A byte-order mark and CRLF line ends are accepted.
// A column is checked only when a reader uses it (column_roles.hpp): a column no reader needs
// may have any name, any unit or none, and cells that are not numbers. Everything else that is
// malformed (bytes that are not UTF-8 text, a NUL byte, no names row, no data rows, a row with
// more values than names) is a DataError naming file:row:column and what to do; nothing is
// guessed. Cells are quoted in messages as printable text.
#pragma once

#include "lang/model.hpp"
#include "runtime/core/drive.hpp"

#include <optional>
#include <string>
#include <vector>

namespace rheo::runtime {

struct Table {
  std::string path;
  std::string step;                               // the TRIOS step read; empty for a plain table
  int header_row = 0;                             // 1-based file line of the names row
  int units_row = 0;                              // 1-based file line of the units row; 0: units in the names
  std::vector<std::string> names;                 // as written, without the unit: "time", "Storage modulus"
  std::vector<std::string> units;                 // as written: "s", "MPa"; "" when none is given
  std::vector<int> unit_columns;                  // 1-based byte column of each unit (of the name when none)
  std::vector<std::optional<lang::Unit>> parsed;  // each unit; nullopt when none is given or it is unknown
  std::vector<std::vector<double>> columns;       // internal units (as written when the unit is not known),
                                                  // NaN where a cell is not a number
  std::vector<std::string> problems;              // per column: its first fault as a whole error message; "" if none
  std::vector<int> rows;                          // 1-based file line of each data row
  std::vector<int> cell_columns;                  // 1-based byte column of each cell, row-major

  // The column named NAME (case and spacing aside: "Storage  Modulus" is "storage modulus"); -1
  // when absent.
  int column(const std::string& name) const;
  // Byte column (1-based) of field `field` in data row `row_index` (0-based), for file:row:col.
  int cell_column(std::size_t row_index, int field) const;
};

// NAME for matching: ASCII lower case, '_' as a space, runs of spaces as one, trimmed.
std::string column_key(std::string_view name);
// A unit as instruments write it, read: "um", "µm" and "μm"; "°" for deg; "%"; "-", "1" or
// nothing for a plain number; "N/mm²". nullopt when unknown.
std::optional<lang::Unit> table_unit(std::string_view text);

// "file:row:1: error: " at the header, for a message about the table's columns or kind.
std::string header_error(const Table& table);
// "the header has: time, force", printable.
std::string header_columns(const Table& table);

// NAMED_AT, when given, is where a .rheo file names PATH: a file that cannot be read is then
// reported there (file:line:col of the name), since that is where to fix it. The table is held
// whole, so its file may have at most lang::max_table_bytes (a history protocol's file is
// streamed instead where it can be: history_stream.hpp).
// STEP picks a TRIOS step (table_layout.hpp).
Table read_table(const std::string& path, const lang::SourceLocation* named_at = nullptr, const std::string& step = "");
Table parse_table(const std::string& path, const std::string& text, const std::string& step = "");
// The message of a DataError for a table that cannot be read (FAILURE, ADVICE: lang::FileText).
std::string unreadable_table(const std::string& path, const lang::SourceLocation* named_at, const std::string& failure, const char* advice);

// A displacement history from a table with "time" and "displacement" columns: strictly
// increasing time; its first displacement is where the network starts relaxed
// (stepping/relaxed_state.hpp), or, with FROM_REST, must be 0 (within 1e-9 mm). Time is shifted
// so that the drive starts at t = 0.
// READING names the columns (column_roles.hpp).
struct ColumnReading;
Drive drive_from_table(const Table& table, bool from_rest = false);
Drive drive_from_table(const Table& table, const ColumnReading& reading, bool from_rest = false);

}  // namespace rheo::runtime
