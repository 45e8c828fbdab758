// A table cell read as a number, without allocating: std::from_chars (correctly rounded, as
// strtod is, in no locale), after one optional leading '+', with ',' read as the decimal point
// where the table's layout has a decimal comma (table_layout.hpp). Cells are at most a line of
// a file; the conversion of a decimal comma copies only cells longer than 64 bytes.
#pragma once

#include <string>
#include <string_view>

namespace rheo::runtime {

enum class CellNumber {
  number,        // VALUE holds it (it may be inf or nan: from_chars reads "inf" and "nan")
  empty,         // nothing (or a lone '+')
  not_a_number,  // text that is not wholly a number
  out_of_range,  // a number past the range of a double ("1e400")
};

// CELL read as a number into VALUE (set only for CellNumber::number).
CellNumber read_cell_number(std::string_view cell, bool decimal_comma, double& value);

// CELL as read_cell_number reads it (the '+' dropped, a decimal comma made a point), for
// messages that quote it.
std::string cell_as_read(std::string_view cell, bool decimal_comma);

}  // namespace rheo::runtime
