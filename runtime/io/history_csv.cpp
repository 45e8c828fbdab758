#include "runtime/io/history_csv.hpp"

#include "lang/file_text.hpp"
#include "lang/limits.hpp"
#include "lang/text_encoding.hpp"
#include "lang/units.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/io/column_roles.hpp"
#include "runtime/io/drive_faults.hpp"
#include "runtime/io/table_layout.hpp"
#include "runtime/io/table_rows.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>

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

namespace {

Table parse_utf8(const std::string& path, const std::string& text, const std::string& step) {
  Table table;
  table.path = path;
  if (const auto problem = lang::find_encoding_problem(text)) {
    const lang::TextPosition p = lang::position_of(text, problem->offset);
    fail(path, p.line, p.column, problem->description);
  }
  const TableLayout layout = find_layout(path, text, step);
  table.step = layout.step;
  TableRows rows(table, layout);
  const std::string_view body = std::string_view(text).substr(layout.begin, layout.end - layout.begin);
  int row = layout.first_row - 1;
  for (std::size_t start = 0; start < body.size();) {
    auto newline = body.find('\n', start);
    if (newline == std::string_view::npos) newline = body.size();
    rows.line(body.substr(start, newline - start), ++row);
    start = newline + 1;
  }
  rows.finish(table.rows.size());
  return table;
}

}  // namespace

std::string unreadable_table(const std::string& path, const lang::SourceLocation* named_at, const std::string& failure, const char* advice) {
  if (named_at)
    return fmt::format("{}cannot read '{}', named here ({}); {} (a relative name is relative to the .rheo file)", error_at(*named_at),
                       lang::printable(path), failure, advice);
  return fmt::format("{}: error: cannot read the file ({}); {}", lang::printable(path), failure, advice);
}

Table read_table(const std::string& path, const lang::SourceLocation* named_at, const std::string& step) {
  lang::FileText table = lang::read_file_text(path, lang::max_table_bytes);
  if (!table.failure.empty() && table.failure.rfind("it is larger than", 0) == 0)
    throw DataError(unreadable_table(path, named_at,
                                     fmt::format("it is larger than {} MiB, the most rheo holds as a whole table; `rheo simulate` streams a history "
                                                 "file of any size when it writes the history as CSV or HDF5 on the fixed-step solver, "
                                                 "`rheo fit` and `report` a measured history in a regular file",
                                                 lang::max_table_bytes >> 20),
                                     table.advice()));
  if (!table.failure.empty()) throw DataError(unreadable_table(path, named_at, table.failure, table.advice()));
  return parse_utf8(path, text_as_utf8(path, std::move(table.text)), step);
}

Table parse_table(const std::string& path, const std::string& raw, const std::string& step) {
  return parse_utf8(path, text_as_utf8(path, raw), step);
}

Drive drive_from_table(const Table& table, bool from_rest) { return drive_from_table(table, ColumnReading{}, from_rest); }

namespace drive_faults {

std::string missing_columns(const Table& table) {
  return fmt::format("{}a displacement history needs columns 'time [s]' and 'displacement [mm]' (any time and length units); {}",
                     header_error(table), header_columns(table));
}

std::string too_few_rows(const std::string& path, int row) {
  return fmt::format("{}:{}:1: error: a history needs at least two rows (where it starts and where it goes); add rows", path, row);
}

bool starts_at_rest(double u0, double largest) { return !(std::abs(u0) > 1e-9 * largest); }

std::string not_at_rest(const std::string& path, int row, int column, double u0) {
  return fmt::format(
      "{}:{}:{}: error: with start = rest the history must start from rest (displacement 0 in its first row, found {} mm); add a first row "
      "with displacement 0, or start relaxed at the first displacement (start = relaxed, the default)",
      path, row, column, u0);
}

std::string time_not_increasing(const std::string& path, int row, int column, double t, double t_before, int row_before) {
  return fmt::format(
      "{}:{}:{}: error: time must increase strictly (row {} has {:g} s after {:g} s at row {}); sort the rows by time and remove repeated ones",
      path, row, column, row, t, t_before, row_before);
}

bool drivable(double u) { return std::abs(u) <= lang::max_amplitude; }

std::string not_drivable(const std::string& path, int row, int column, double u) {
  return fmt::format("{}:{}:{}: error: displacement {:g} mm is beyond the {:g} mm a rig can drive; check the column's unit", path, row, column, u,
                     lang::max_amplitude);
}

std::string missing_force(const Table& table) {
  return fmt::format("{}a measured history needs a column 'force [N]' (any force unit) next to time and displacement; {}", header_error(table),
                     header_columns(table));
}

std::string zero_force(const std::string& path, int row, int column) {
  return fmt::format("{}:{}:{}: error: every measured force is zero; a fit needs a force signal: check the force column and its unit", path, row,
                     column);
}

}  // namespace drive_faults

Drive drive_from_table(const Table& table, const ColumnReading& reading, bool from_rest) {
  const int t = find_role(table, Role::time, reading), u = find_role(table, Role::displacement, reading);
  if (t < 0 || u < 0) throw DataError(drive_faults::missing_columns(table));
  const std::vector<double> time = role_values(table, t, Role::time, reading);
  const std::vector<double> disp = role_values(table, u, Role::displacement, reading);
  if (time.size() < 2) throw DataError(drive_faults::too_few_rows(table.path, table.rows[0]));
  double largest = 0.0;
  for (double x : disp) largest = std::max(largest, std::abs(x));
  if (from_rest && !drive_faults::starts_at_rest(disp[0], largest))
    throw DataError(drive_faults::not_at_rest(table.path, table.rows[0], table.cell_column(0, u), disp[0]));
  Drive d;
  for (std::size_t i = 0; i < time.size(); ++i) {
    if (i > 0 && !(time[i] > time[i - 1]))
      throw DataError(drive_faults::time_not_increasing(table.path, table.rows[i], table.cell_column(i, t), time[i], time[i - 1], table.rows[i - 1]));
    if (!drive_faults::drivable(disp[i])) throw DataError(drive_faults::not_drivable(table.path, table.rows[i], table.cell_column(i, u), disp[i]));
    d.time.push_back(time[i] - time[0]);
    d.displacement.push_back(disp[i]);
  }
  return d;
}

}  // namespace rheo::runtime
