// Where a table sits in a file's text and how its cells are written, as instruments export them
// (docs/data-formats.md):
//   - plain tables: `#` comment lines, then a names row, an optional units row, data rows;
//     cells separated by ',' ';' or tab, whichever the names row uses most (ties: tab, ';', ','),
//     a decimal comma accepted where the delimiter is not ',';
//   - TA Instruments TRIOS text exports: `[step]` sections, each a step name line, a names row,
//     a units row and data rows up to a blank line; one step is the table (STEP);
//   - Excel workbooks (.xls, .xlsx, .ods) are recognised and refused with what to do; UTF-16 text
//     with a byte-order mark (as some Windows instrument software writes) is read as UTF-8.
// Errors are DataErrors naming file:row:column.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace rheo::runtime {

struct TableLayout {
  std::size_t begin = 0;           // byte offset of the first line to read (the names row or before)
  std::size_t end = 0;             // byte offset past the last line to read
  int first_row = 1;               // 1-based file line at `begin`
  char delimiter = ',';            // between cells
  bool decimal_comma = false;      // "1,5" is 1.5 (only where the delimiter is not ',')
  bool units_row = false;          // a units row follows the names row (TRIOS)
  std::string step;                // the TRIOS step read, as the file names it; empty otherwise
  std::vector<std::string> steps;  // every TRIOS step the file has
};

// TEXT as UTF-8: converted from UTF-16 when it starts with a UTF-16 byte-order mark, its UTF-8
// byte-order mark removed; an Excel workbook or an HDF5 file is a DataError.
std::string text_as_utf8(const std::string& path, std::string text);
// The parts of that for a file read piece by piece: a DataError for an HDF5 file or a workbook (PATH's
// extension, or START, the file's first kSignatureBytes bytes, says so); whether START is a UTF-16
// byte-order mark.
inline constexpr std::size_t kSignatureBytes = 32;  // the longest signature, MATLAB's, is 19 bytes
void refuse_workbook(const std::string& path, std::string_view start);
bool is_utf16(std::string_view start);

// The layout of TEXT (the file PATH, for messages). STEP picks a TRIOS step: the step's name as
// written or without its " - N" counter, case-insensitively; empty: the file's only step.
TableLayout find_layout(const std::string& path, std::string_view text, const std::string& step);

// A plain table's layout is read from its first line that, trimmed of spaces, tabs and CRs, is
// neither empty nor a '#' comment (HOLDS_LAYOUT): the delimiter that line uses most, a decimal
// comma unless that is ','. BEGIN and END are left to the caller.
bool holds_layout(std::string_view line);
TableLayout plain_layout(std::string_view line);

// The delimiter a names row uses: the most frequent of tab, ';' and ',' outside quotes (ties
// in that order); ',' when it has none.
char detect_delimiter(std::string_view names_row);

struct Cell {
  std::string_view text;  // trimmed, surrounding double quotes removed ("" inside quotes is one ")
  int column;             // 1-based byte column where the cell starts
};
// The cells of LINE into CELLS (replacing what it held), without allocating once CELLS and
// SCRATCH have grown to a line's size: a cell's text views LINE, or SCRATCH where a quoted cell
// holds "" (SCRATCH is cleared). The views live as long as LINE and SCRATCH are unchanged.
void split_cells(std::string_view line, char delimiter, std::vector<Cell>& cells, std::string& scratch);

// Whether LINE, trimmed and in any case, is "[step]": a TRIOS export's section line.
bool is_step_line(std::string_view line);

}  // namespace rheo::runtime
