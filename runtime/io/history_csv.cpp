#include "runtime/io/history_csv.hpp"

#include "lang/file_text.hpp"
#include "lang/limits.hpp"
#include "lang/text_encoding.hpp"
#include "lang/units.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/io/column_roles.hpp"
#include "runtime/io/table_layout.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <cctype>
#include <limits>
#include <utility>

namespace rheo::runtime {
namespace {

[[noreturn]] void fail(const std::string& path, int row, int column, const std::string& message) {
  throw DataError(fmt::format("{}:{}:{}: error: {}", path, row, column, message));
}

std::string trim(std::string_view s) {
  const auto begin = s.find_first_not_of(" \t");
  if (begin == std::string_view::npos) return {};
  const auto end = s.find_last_not_of(" \t");
  return std::string(s.substr(begin, end - begin + 1));
}

// "Storage modulus (MPa)" -> ("Storage modulus", "MPa", offset of "MPa"); a bracketed unit always,
// a parenthesised one only when it is a unit rheo reads ("Stress (step)" is a name).
struct NameAndUnit {
  std::string name, unit;
  std::size_t unit_offset = 0;  // in the cell; 0 when there is no unit
};
NameAndUnit split_name(const std::string& cell) {
  for (const auto& [open_char, close_char] : {std::pair{'[', ']'}, std::pair{'(', ')'}}) {
    const auto close = cell.rfind(close_char);
    const auto open = cell.rfind(open_char);
    if (close != cell.size() - 1 || open == std::string::npos || cell.empty()) continue;
    std::string unit = trim(std::string_view(cell).substr(open + 1, close - open - 1));
    if (open_char == '(' && (unit.empty() || !table_unit(unit))) continue;
    return {trim(std::string_view(cell).substr(0, open)), unit.empty() ? "-" : unit, open + 1};
  }
  return {cell, "", 0};
}

bool is_number(std::string text, bool decimal_comma) {
  if (!text.empty() && text.front() == '+') text.erase(0, 1);
  if (decimal_comma)
    for (char& c : text)
      if (c == ',') c = '.';
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return !text.empty() && ptr == text.data() + text.size() && (ec == std::errc{} || ec == std::errc::result_out_of_range);
}

// A units row: the names carry no units and no cell of ROW is a number.
bool is_units_row(const std::vector<Cell>& cells, bool decimal_comma) {
  bool any = false;
  for (const auto& c : cells) {
    if (c.text.empty()) continue;
    if (is_number(c.text, decimal_comma)) return false;
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

class TableReader {
 public:
  TableReader(Table& table, const TableLayout& layout) : t_(table), layout_(layout) {}

  void names(const std::vector<Cell>& cells, int row) {
    t_.header_row = row;
    for (const auto& cell : cells) {
      const NameAndUnit n = layout_.units_row ? NameAndUnit{cell.text, "", 0} : split_name(cell.text);
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
                                              t_.path, row, cells[i].column, lang::printable(t_.names[i]), first + 1, i + 1);
        t_.problems[i] = t_.problems[static_cast<std::size_t>(first)] = twice;
      }
    }
  }

  // The row under the names: their units when the layout says so or when it looks like units.
  bool units(const std::vector<Cell>& cells, int row) {
    if (!layout_.units_row && (units_in_names_ || !is_units_row(cells, layout_.decimal_comma))) return false;
    t_.units_row = row;
    for (std::size_t i = 0; i < t_.names.size(); ++i) {
      t_.units[i] = i < cells.size() ? cells[i].text : "";
      t_.unit_columns[i] = i < cells.size() ? cells[i].column : 1;
      t_.parsed[i] = t_.units[i].empty() ? std::nullopt : table_unit(t_.units[i]);
    }
    return true;
  }

  // Data row ROW: a value per column in internal units; a cell that is not a finite number is
  // NaN and its column's problem, reported when a reader uses the column.
  void data(const std::vector<Cell>& cells, int row) {
    const std::size_t n = t_.names.size();
    std::size_t given = cells.size();
    while (given > n && cells[given - 1].text.empty()) --given;
    if (given > n)
      fail(t_.path, row, cells[n].column,
           fmt::format("this row has {} values, the header has {} columns; add names for the extra columns or remove them", given, n));
    for (std::size_t c = 0; c < n; ++c) {
      const int column = c < cells.size() ? cells[c].column : 1;
      t_.cell_columns.push_back(column);
      t_.columns[c].push_back(c < cells.size() ? value(cells[c].text, c, row, column)
                                               : missing(c, row, fmt::format("this row has {} values, the header has {} columns", given, n)));
    }
    t_.rows.push_back(row);
  }

 private:
  double missing(std::size_t c, int row, const std::string& message, int column = 1) {
    if (t_.problems[c].empty()) t_.problems[c] = fmt::format("{}:{}:{}: error: {}", t_.path, row, column, message);
    return std::numeric_limits<double>::quiet_NaN();
  }

  double value(std::string s, std::size_t c, int row, int column) {
    const std::string& name = t_.names[c];
    if (!s.empty() && s.front() == '+') s.erase(0, 1);
    if (layout_.decimal_comma)
      for (char& ch : s)
        if (ch == ',') ch = '.';
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || (ec != std::errc{} && ec != std::errc::result_out_of_range) || ptr != s.data() + s.size())
      return missing(c, row,
                     s.empty() ? fmt::format("empty cell in column '{}'; fill it or remove the row", lang::printable(name))
                               : fmt::format("'{}' is not a number (column '{}'); write a number such as 0.25 or 1e-3{}", lang::printable(s),
                                             lang::printable(name), unit_hint(s)),
                     column);
    if (ec == std::errc::result_out_of_range || !std::isfinite(v))
      return missing(c, row,
                     fmt::format("'{}' is not a finite number (column '{}'); remove or repair the row", lang::printable(s), lang::printable(name)),
                     column);
    const double scale = t_.parsed[c] ? t_.parsed[c]->scale : 1.0;
    if (!std::isfinite(v * scale))
      return missing(c, row,
                     fmt::format("'{}' {} overflows a double (column '{}'); remove or repair the row", lang::printable(s),
                                 lang::printable(t_.units[c]), lang::printable(name)),
                     column);
    return v * scale;
  }

  Table& t_;
  const TableLayout& layout_;
  bool units_in_names_ = false;
};

}  // namespace

std::string header_error(const Table& table) { return fmt::format("{}:{}:1: error: ", table.path, table.header_row); }

std::string header_hint(const Table& table);

std::string header_columns(const Table& table) {
  constexpr std::size_t shown = 24;
  std::string names;
  for (std::size_t i = 0; i < std::min(shown, table.names.size()); ++i) names += (names.empty() ? "" : ", ") + lang::printable(table.names[i]);
  if (table.names.size() > shown) names += fmt::format(", ... ({} columns)", table.names.size());
  return "the header has: " + names + header_hint(table);
}

// What a names row that almost matches seems to be: one cell holding another separator, or a
// row of units where the names belong.
std::string header_hint(const Table& table) {
  if (table.names.size() == 1) {
    for (const char c : std::string_view("|:/ ")) {
      if (table.names[0].find(c) == std::string::npos) continue;
      return fmt::format(
          "; rheo separates cells by ',', ';' or tab, and this names row is one cell: is {} its separator? export the table "
          "with commas, semicolons or tabs",
          c == ' ' ? std::string("a space") : fmt::format("'{}'", c));
    }
    return "";
  }
  const bool all_units = std::all_of(table.names.begin(), table.names.end(), [](const std::string& name) {
    return !name.empty() && table_unit(name) && !std::isdigit(static_cast<unsigned char>(name.front()));
  });
  const bool dimensioned = std::any_of(table.names.begin(), table.names.end(), [](const std::string& name) {
    const auto unit = table_unit(name);
    return unit && !unit->dimension.dimensionless();
  });
  return all_units && dimensioned ? "; these look like units: put the names row first and the units row directly under it, or write 'name [unit]'"
                                  : "";
}

int Table::cell_column(std::size_t row_index, int field) const {
  return cell_columns.at(row_index * names.size() + static_cast<std::size_t>(field));
}

std::string column_key(std::string_view name) {
  std::string key;
  for (char c : name) {
    if (c == '_' || c == '\t') c = ' ';
    if (c == ' ' && (key.empty() || key.back() == ' ')) continue;
    key += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  if (!key.empty() && key.back() == ' ') key.pop_back();
  return key;
}

std::optional<lang::Unit> table_unit(std::string_view text) {
  std::string unit = trim(text);
  if (unit.empty() || unit == "-" || unit == "1") return lang::Unit{};
  if (unit == "\xC2\xB0" || unit == "\xC2\xBA") return lang::unit_atom("deg");  // ° and º
  for (const auto& [from, to] :
       {std::pair<std::string_view, std::string_view>{"\xC2\xB5", "u"}, {"\xCE\xBC", "u"}, {"\xC2\xB2", "^2"}, {"\xC2\xB3", "^3"}, {" ", ""}})
    for (auto at = unit.find(from); at != std::string::npos; at = unit.find(from, at + to.size())) unit.replace(at, from.size(), to);
  return lang::parse_unit(unit);
}

int Table::column(const std::string& name) const {
  const std::string key = column_key(name);
  for (std::size_t i = 0; i < names.size(); ++i)
    if (column_key(names[i]) == key) return static_cast<int>(i);
  return -1;
}

Table read_table(const std::string& path, const lang::SourceLocation* named_at, const std::string& step) {
  const lang::FileText table = lang::read_file_text(path, lang::max_table_bytes);
  if (!table.failure.empty() && named_at)
    throw DataError(fmt::format("{}cannot read '{}', named here ({}); {} (a relative name is relative to the .rheo file)", error_at(*named_at),
                                lang::printable(path), table.failure, table.advice()));
  if (!table.failure.empty())
    throw DataError(fmt::format("{}: error: cannot read the file ({}); {}", lang::printable(path), table.failure, table.advice()));
  return parse_table(path, table.text, step);
}

Table parse_table(const std::string& path, const std::string& raw, const std::string& step) {
  Table table;
  table.path = path;
  const std::string text = text_as_utf8(path, raw);
  if (const auto problem = lang::find_encoding_problem(text)) {
    const lang::TextPosition p = lang::position_of(text, problem->offset);
    fail(path, p.line, p.column, problem->description);
  }
  const TableLayout layout = find_layout(path, text, step);
  table.step = layout.step;
  TableReader reader(table, layout);
  const std::string_view body = std::string_view(text).substr(layout.begin, layout.end - layout.begin);
  int row = layout.first_row - 1;
  bool under_names = false;
  for (std::size_t start = 0; start < body.size();) {
    auto newline = body.find('\n', start);
    if (newline == std::string_view::npos) newline = body.size();
    std::string_view line = body.substr(start, newline - start);
    start = newline + 1;
    ++row;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const std::string stripped = trim(line);
    if (stripped.empty() || stripped.front() == '#') continue;
    const auto cells = split_cells(line, layout.delimiter);
    if (table.names.empty()) {
      reader.names(cells, row);
      under_names = true;
      continue;
    }
    if (std::exchange(under_names, false) && reader.units(cells, row)) continue;
    reader.data(cells, row);
  }
  if (table.names.empty())
    fail(path, 1, 1, "no header found: the file is empty or holds only comments; start it with a header line such as 'time [s],displacement [mm]'");
  if (table.rows.empty())
    fail(path, table.header_row, 1,
         fmt::format("the table has a header but no data rows; add rows of numbers below it{}",
                     table.names.size() == 1 ? " (the header has one column: are the lines above the table notes? start them with '#')" : ""));
  return table;
}

Drive drive_from_table(const Table& table, bool from_rest) { return drive_from_table(table, ColumnReading{}, from_rest); }

Drive drive_from_table(const Table& table, const ColumnReading& reading, bool from_rest) {
  const int t = find_role(table, Role::time, reading), u = find_role(table, Role::displacement, reading);
  if (t < 0 || u < 0)
    throw DataError(fmt::format("{}a displacement history needs columns 'time [s]' and 'displacement [mm]' (any time and length units); {}",
                                header_error(table), header_columns(table)));
  const std::vector<double> time = role_values(table, t, Role::time, reading);
  const std::vector<double> disp = role_values(table, u, Role::displacement, reading);
  if (time.size() < 2) fail(table.path, table.rows[0], 1, "a history needs at least two rows (where it starts and where it goes); add rows");
  // Rest within 1e-9 of the history's largest displacement (any scale of the physical range).
  double largest = 0.0;
  for (double x : disp) largest = std::max(largest, std::abs(x));
  if (from_rest && std::abs(disp[0]) > 1e-9 * largest)
    fail(table.path, table.rows[0], table.cell_column(0, u),
         fmt::format("with start = rest the history must start from rest (displacement 0 in its first row, found {} mm); add a first row "
                     "with displacement 0, or start relaxed at the first displacement (start = relaxed, the default)",
                     disp[0]));
  Drive d;
  for (std::size_t i = 0; i < time.size(); ++i) {
    if (i > 0 && !(time[i] > time[i - 1]))
      fail(table.path, table.rows[i], table.cell_column(i, t),
           fmt::format("time must increase strictly (row {} has {:g} s after {:g} s at row {}); sort the rows by time and remove repeated ones",
                       table.rows[i], time[i], time[i - 1], table.rows[i - 1]));
    if (!(std::abs(disp[i]) <= lang::max_amplitude))
      fail(table.path, table.rows[i], table.cell_column(i, u),
           fmt::format("displacement {:g} mm is beyond the {:g} mm a rig can drive; check the column's unit", disp[i], lang::max_amplitude));
    d.time.push_back(time[i] - time[0]);
    d.displacement.push_back(disp[i]);
  }
  return d;
}

}  // namespace rheo::runtime
