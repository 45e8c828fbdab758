#include "runtime/io/fit_data.hpp"

#include "runtime/core/errors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace rheo::runtime {

HistoryData history_data_from_table(const Table& table) {
  const int f = table.column("force");
  if (f < 0)
    throw DataError(fmt::format("{}a measured history needs a column 'force [N]' (any force unit) next to time and displacement; {}",
                                header_error(table), header_columns(table)));
  HistoryData h;
  h.path = table.path;
  h.drive = drive_from_table(table);
  h.force = table.columns[static_cast<std::size_t>(f)];
  h.rows = table.rows;
  h.force_scale = 0.0;
  for (double v : h.force) h.force_scale = std::max(h.force_scale, std::abs(v));
  if (!(h.force_scale > 0.0))
    throw DataError(fmt::format("{}:{}:{}: error: every measured force is zero; a fit needs a force signal: check the force column and its unit",
                                table.path, table.rows.front(), table.cell_column(0, f)));
  return h;
}

FitDataSet read_fit_data(const std::string& path, double weight, const lang::SourceLocation* named_at) {
  const Table table = read_table(path, named_at);
  FitDataSet set{path, weight, HarmonicData{}};
  if (table.column("amplitude") >= 0 && table.column("frequency") >= 0) {
    set.data = harmonic_data_from_table(table);
  } else if (table.column("time") >= 0) {
    set.data = history_data_from_table(table);
  } else {
    throw DataError(
        fmt::format("{}cannot tell what this data is; a harmonic table needs 'amplitude', 'frequency' and 'stiffness'+'phase' or "
                    "'storage'+'loss' columns, a history needs 'time', 'displacement' and 'force'; {}",
                    header_error(table), header_columns(table)));
  }
  return set;
}

}  // namespace rheo::runtime
