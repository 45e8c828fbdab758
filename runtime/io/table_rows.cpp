#include "runtime/io/table_rows.hpp"

#include "lang/text_encoding.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/io/cell_number.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace rheo::runtime {
namespace {

[[noreturn]] void fail(const std::string& path, int row, int column, const std::string& message) {
  throw DataError(fmt::format("{}:{}:{}: error: {}", path, row, column, message));
}

std::string_view trim(std::string_view s) {
  const auto begin = s.find_first_not_of(" \t");
  if (begin == std::string_view::npos) return {};
  return s.substr(begin, s.find_last_not_of(" \t") - begin + 1);
}

// "Storage modulus (MPa)" -> ("Storage modulus", "MPa", offset of "MPa"); a bracketed unit always,
// a parenthesised one only when it is a unit rheo reads ("Stress (step)" is a name).
struct NameAndUnit {
  std::string name, unit;
  std::size_t unit_offset = 0;  // in the cell; 0 when there is no unit
};
NameAndUnit split_name(std::string_view cell) {
  for (const auto& [open_char, close_char] : {std::pair{'[', ']'}, std::pair{'(', ')'}}) {
    const auto close = cell.rfind(close_char);
    const auto open = cell.rfind(open_char);
    if (close != cell.size() - 1 || open == std::string::npos || cell.empty()) continue;
    std::string unit(trim(cell.substr(open + 1, close - open - 1)));
    if (open_char == '(' && (unit.empty() || !table_unit(unit))) continue;
    return {std::string(trim(cell.substr(0, open))), unit.empty() ? "-" : unit, open + 1};
  }
  return {std::string(cell), "", 0};
}

// A units row: the names carry no units and no cell of ROW is a number.
bool is_units_row(const std::vector<Cell>& cells, bool decimal_comma) {
  bool any = false;
  for (const auto& c : cells) {
    if (c.text.empty()) continue;
    double value = 0.0;
    const CellNumber read = read_cell_number(c.text, decimal_comma, value);
    if (read == CellNumber::number || read == CellNumber::out_of_range) return false;
    any = true;
  }
  return any;
}

// For a cell that is not a number but reads as a unit: where units go.
std::string unit_hint(const std::string& cell) {
  const bool letters = std::any_of(cell.begin(), cell.end(), [](char c) { return std::isalpha(static_cast<unsigned char>(c)); });
  if (!letters || !table_unit(cell)) return "";
  return fmt::format(" ('{}' reads as a unit: units go in the names row, 'name [unit]', or in a units row directly under it)", lang::printable(cell));
}

}  // namespace

bool TableRows::skips(std::string_view line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  const std::string_view stripped = trim(line);
  return stripped.empty() || stripped.front() == '#';
}

void TableRows::line(std::string_view line, int row) {
  if (skips(line)) return;
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  split_cells(line, layout_.delimiter, cells_, scratch_);
  if (t_.names.empty()) {
    names(row);
    under_names_ = true;
    return;
  }
  if (std::exchange(under_names_, false) && units(row)) return;
  data(row);
}

void TableRows::finish(std::size_t data_rows) const {
  if (t_.names.empty())
    fail(t_.path, 1, 1,
         "no header found: the file is empty or holds only comments; start it with a header line such as 'time [s],displacement [mm]'");
  if (data_rows == 0)
    fail(t_.path, t_.header_row, 1,
         fmt::format("the table has a header but no data rows; add rows of numbers below it{}",
                     t_.names.size() == 1 ? " (the header has one column: are the lines above the table notes? start them with '#')" : ""));
}

void TableRows::names(int row) {
  t_.header_row = row;
  for (const auto& cell : cells_) {
    const NameAndUnit n = layout_.units_row ? NameAndUnit{std::string(cell.text), "", 0} : split_name(cell.text);
    t_.names.push_back(n.name);
    t_.units.push_back(n.unit);
    t_.unit_columns.push_back(cell.column + static_cast<int>(n.unit_offset));
    t_.parsed.push_back(n.unit.empty() ? std::nullopt : table_unit(n.unit));
    t_.problems.emplace_back();
    units_in_names_ = units_in_names_ || !n.unit.empty();
  }
  t_.columns.resize(t_.names.size());
  for (std::size_t i = 0; i < t_.names.size(); ++i) {
    const int first = t_.column(t_.names[i]);
    if (first >= 0 && static_cast<std::size_t>(first) != i) {
      const std::string twice = fmt::format("{}:{}:{}: error: column '{}' appears twice in the header (columns {} and {}); rename or remove one",
                                            t_.path, row, cells_[i].column, lang::printable(t_.names[i]), first + 1, i + 1);
      t_.problems[i] = t_.problems[static_cast<std::size_t>(first)] = twice;
    }
  }
}

// The row under the names: their units when the layout says so or when it looks like units.
bool TableRows::units(int row) {
  if (!layout_.units_row && (units_in_names_ || !is_units_row(cells_, layout_.decimal_comma))) return false;
  t_.units_row = row;
  for (std::size_t i = 0; i < t_.names.size(); ++i) {
    t_.units[i] = i < cells_.size() ? std::string(cells_[i].text) : "";
    t_.unit_columns[i] = i < cells_.size() ? cells_[i].column : 1;
    t_.parsed[i] = t_.units[i].empty() ? std::nullopt : table_unit(t_.units[i]);
  }
  return true;
}

// Data row ROW: a value per column in internal units; a cell that is not a finite number is
// NaN and its column's problem, reported when a reader uses the column.
void TableRows::data(int row) {
  const std::size_t n = t_.names.size();
  std::size_t given = cells_.size();
  while (given > n && cells_[given - 1].text.empty()) --given;
  if (given > n)
    fail(t_.path, row, cells_[n].column,
         fmt::format("this row has {} values, the header has {} columns; add names for the extra columns or remove them", given, n));
  for (std::size_t c = 0; c < n; ++c) {
    const int column = c < cells_.size() ? cells_[c].column : 1;
    t_.cell_columns.push_back(column);
    t_.columns[c].push_back(c < cells_.size() ? value(cells_[c].text, c, row, column)
                                              : missing(c, row, fmt::format("this row has {} values, the header has {} columns", given, n)));
  }
  t_.rows.push_back(row);
}

double TableRows::missing(std::size_t c, int row, const std::string& message, int column) {
  if (t_.problems[c].empty()) t_.problems[c] = fmt::format("{}:{}:{}: error: {}", t_.path, row, column, message);
  return std::numeric_limits<double>::quiet_NaN();
}

double TableRows::value(std::string_view cell, std::size_t c, int row, int column) {
  double v = 0.0;
  const CellNumber read = read_cell_number(cell, layout_.decimal_comma, v);
  if (read == CellNumber::number && std::isfinite(v)) {
    const double scale = t_.parsed[c] ? t_.parsed[c]->scale : 1.0;
    if (std::isfinite(v * scale)) return v * scale;
  }
  // A fault: its column's problem, quoting the cell as read.
  const std::string& name = t_.names[c];
  const std::string s = cell_as_read(cell, layout_.decimal_comma);
  if (read == CellNumber::empty)
    return missing(c, row, fmt::format("empty cell in column '{}'; fill it or remove the row", lang::printable(name)), column);
  if (read == CellNumber::not_a_number)
    return missing(c, row,
                   fmt::format("'{}' is not a number (column '{}'); write a number such as 0.25 or 1e-3{}", lang::printable(s),
                               lang::printable(name), unit_hint(s)),
                   column);
  if (read == CellNumber::out_of_range || !std::isfinite(v))
    return missing(c, row,
                   fmt::format("'{}' is not a finite number (column '{}'); remove or repair the row", lang::printable(s), lang::printable(name)),
                   column);
  return missing(c, row,
                 fmt::format("'{}' {} overflows a double (column '{}'); remove or repair the row", lang::printable(s), lang::printable(t_.units[c]),
                             lang::printable(name)),
                 column);
}

}  // namespace rheo::runtime
