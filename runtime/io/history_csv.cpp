#include "runtime/io/history_csv.hpp"

#include "lang/file_text.hpp"
#include "lang/limits.hpp"
#include "lang/text_encoding.hpp"
#include "lang/units.hpp"
#include "runtime/core/errors.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>

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

struct Cell {
  std::string text;
  int column;  // 1-based byte column of the cell start
};

std::vector<Cell> split(const std::string& line) {
  std::vector<Cell> cells;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    const auto end = comma == std::string::npos ? line.size() : comma;
    cells.push_back({trim(std::string_view(line).substr(start, end - start)), static_cast<int>(start) + 1});
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return cells;
}

// What a reader expects of a column it knows by name: its dimension and a unit to suggest.
// Other columns are not checked.
struct ColumnKind {
  lang::Dimension dimension;
  const char* kind;     // for the message
  const char* example;  // a unit of that kind
};
std::optional<ColumnKind> known_column(std::string_view name) {
  using namespace lang;
  if (name == "time") return ColumnKind{dim::time, "time (s)", "s"};
  if (name == "displacement" || name == "amplitude") return ColumnKind{dim::length, "length (mm)", "mm"};
  if (name == "force") return ColumnKind{dim::force, "force (N)", "N"};
  if (name == "frequency") return ColumnKind{dim::frequency, "frequency (1/s)", "Hz"};
  if (name == "stiffness" || name == "storage" || name == "loss") return ColumnKind{dim::stiffness, "stiffness (N/mm)", "N/mm"};
  if (name == "phase") return ColumnKind{dim::none, "none (a plain number, or deg for a phase)", "deg"};
  if (name == "weight") return ColumnKind{dim::none, "none (a plain number, or deg for a phase)", "-"};
  return std::nullopt;
}

// The header row ROW: each cell 'name [unit]', the unit known and of the kind the column needs,
// no name twice. Appends each column's scale to internal units to SCALES.
void read_header(Table& table, std::vector<double>& scales, const std::vector<Cell>& cells, int row) {
  const std::string& path = table.path;
  for (const auto& cell : cells) {
    const auto open = cell.text.find('['), close = cell.text.rfind(']');
    if (open == std::string::npos || close == std::string::npos || close < open)
      fail(path, row, cell.column,
           fmt::format("header column '{}' has no unit; write it as 'name [unit]', e.g. 'time [s]'", lang::printable(cell.text)));
    const std::string name = trim(std::string_view(cell.text).substr(0, open));
    const std::string unit = trim(std::string_view(cell.text).substr(open + 1, close - open - 1));
    auto parsed = unit.empty() || unit == "-" ? std::optional<lang::Unit>{lang::Unit{}} : lang::parse_unit(unit);
    if (!parsed)
      fail(path, row, cell.column + static_cast<int>(open) + 1,
           fmt::format("unknown unit '{}' in column '{}'; use units such as s, ms, mm, um, m, N, kN, N/mm, Hz, deg", lang::printable(unit),
                       lang::printable(name)));
    if (const auto known = known_column(name); known && parsed->dimension != known->dimension)
      fail(path, row, cell.column + static_cast<int>(open) + 1,
           fmt::format("column '{}' has unit '{}', {}; {} needs a unit of {}, e.g. '{} [{}]'", name, lang::printable(unit),
                       parsed->dimension.dimensionless() ? std::string("a plain number") : "a " + lang::describe(parsed->dimension), name,
                       known->kind, name, known->example));
    if (table.column(name) >= 0)
      fail(path, row, cell.column, fmt::format("column '{}' appears twice in the header; rename or remove one", lang::printable(name)));
    table.names.push_back(name);
    table.units.push_back(unit);
    scales.push_back(parsed->scale);
  }
  table.columns.resize(table.names.size());
  table.header_row = row;
}

// Data row ROW: as many finite numbers as the header has columns, scaled to internal units.
void read_row(Table& table, const std::vector<double>& scales, const std::vector<Cell>& cells, int row) {
  const std::string& path = table.path;
  if (cells.size() != table.names.size())
    fail(path, row, 1, fmt::format("this row has {} values, the header has {} columns", cells.size(), table.names.size()));
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const std::string& s = cells[c].text;
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (s.empty() || (ec != std::errc{} && ec != std::errc::result_out_of_range) || ptr != s.data() + s.size())
      fail(path, row, cells[c].column,
           fmt::format("'{}' is not a number (column '{}'); write a number such as 0.25 or 1e-3", lang::printable(s), table.names[c]));
    if (ec == std::errc::result_out_of_range || !std::isfinite(value))
      fail(path, row, cells[c].column,
           fmt::format("'{}' is not a finite number (column '{}'); remove or repair the row", lang::printable(s), table.names[c]));
    if (!std::isfinite(value * scales[c]))
      fail(path, row, cells[c].column,
           fmt::format("'{}' {} overflows a double (column '{}'); remove or repair the row", lang::printable(s), table.units[c], table.names[c]));
    table.columns[c].push_back(value * scales[c]);
    table.cell_columns.push_back(cells[c].column);
  }
  table.rows.push_back(row);
}

}  // namespace

std::string header_error(const Table& table) { return fmt::format("{}:{}:1: error: ", table.path, table.header_row); }

std::string header_columns(const Table& table) {
  std::string names;
  for (const auto& name : table.names) names += (names.empty() ? "" : ", ") + lang::printable(name);
  return "the header has: " + names;
}

int Table::cell_column(std::size_t row_index, int field) const {
  return cell_columns.at(row_index * names.size() + static_cast<std::size_t>(field));
}

int Table::column(const std::string& name) const {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  return -1;
}

Table read_table(const std::string& path, const lang::SourceLocation* named_at) {
  const lang::FileText table = lang::read_file_text(path, lang::max_table_bytes);
  if (!table.failure.empty() && named_at)
    throw DataError(fmt::format("{}cannot read '{}', named here ({}); {} (a relative name is relative to the .rheo file)", error_at(*named_at),
                                lang::printable(path), table.failure, table.advice()));
  if (!table.failure.empty())
    throw DataError(fmt::format("{}: error: cannot read the file ({}); {}", lang::printable(path), table.failure, table.advice()));
  return parse_table(path, table.text);
}

Table parse_table(const std::string& path, const std::string& raw) {
  Table table;
  table.path = path;
  std::string text = raw;
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);
  if (const auto problem = lang::find_encoding_problem(text)) {
    const lang::TextPosition p = lang::position_of(text, problem->offset);
    fail(path, p.line, p.column, problem->description);
  }
  std::istringstream lines(text);
  std::string line;
  int row = 0;
  std::vector<double> scales;
  while (std::getline(lines, line)) {
    ++row;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string stripped = trim(line);
    if (stripped.empty() || stripped.front() == '#') continue;
    const auto cells = split(line);
    if (table.names.empty()) read_header(table, scales, cells, row);
    else read_row(table, scales, cells, row);
  }
  if (table.names.empty())
    fail(path, 1, 1, "no header found: the file is empty or holds only comments; start it with a header line such as 'time [s],displacement [mm]'");
  if (table.rows.empty()) fail(path, table.header_row, 1, "the table has a header but no data rows; add rows of numbers below it");
  return table;
}

Drive drive_from_table(const Table& table) {
  const int t = table.column("time"), u = table.column("displacement");
  if (t < 0 || u < 0)
    throw DataError(fmt::format("{}a displacement history needs columns 'time [s]' and 'displacement [mm]' (any time and length units); {}",
                                header_error(table), header_columns(table)));
  const auto& time = table.columns[static_cast<std::size_t>(t)];
  const auto& disp = table.columns[static_cast<std::size_t>(u)];
  if (time.size() < 2) fail(table.path, table.rows[0], 1, "a history needs at least two rows (a start from rest and where it goes); add rows");
  if (std::abs(disp[0]) > 1e-9)
    fail(table.path, table.rows[0], table.cell_column(0, u),
         fmt::format("the history must start from rest (displacement 0 in its first row, found {} mm); add a first row with displacement 0", disp[0]));
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
