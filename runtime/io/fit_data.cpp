#include "runtime/io/fit_data.hpp"

#include "lang/text_encoding.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/io/hdf5_history.hpp"
#include "runtime/io/matlab_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rheo::runtime {

HistoryData history_data_from_table(const Table& table) { return history_data_from_table(table, DataReading{}); }

HistoryData history_data_from_table(const Table& table, const DataReading& reading) {
  const int f = find_role(table, Role::force, reading.columns);
  if (f < 0)
    throw DataError(fmt::format("{}a measured history needs a column 'force [N]' (any force unit) next to time and displacement; {}",
                                header_error(table), header_columns(table)));
  HistoryData h;
  h.path = table.path;
  h.drive = drive_from_table(table, reading.columns);
  h.force = role_values(table, f, Role::force, reading.columns);
  h.rows = table.rows;
  h.force_scale = 0.0;
  for (double v : h.force) h.force_scale = std::max(h.force_scale, std::abs(v));
  if (!(h.force_scale > 0.0))
    throw DataError(fmt::format("{}:{}:{}: error: every measured force is zero; a fit needs a force signal: check the force column and its unit",
                                table.path, table.rows.front(), table.cell_column(0, f)));
  return h;
}

FitDataSet read_fit_data(const std::string& path, double weight, const lang::SourceLocation* named_at, const DataReading& reading) {
  if (reads_as_hdf5(path)) {
    const char* unused = !reading.step.empty()                                  ? "step (of a TRIOS export)"
                         : reading.columns.area || reading.columns.height       ? "area and height (of material data)"
                         : reading.amplitude || reading.strain_amplitude        ? "amplitude (of a harmonic table)"
                         : reading.duplicates != lang::DuplicatePoints::average ? "duplicates (of a harmonic table)"
                                                                                : nullptr;
    if (unused)
      throw DataError(fmt::format("{}: error: {} file is read as a history, so the data line's {} does not apply; remove it", lang::printable(path),
                                  is_matlab_name(path) ? "a MATLAB" : "an HDF5", unused));
    return {path, weight, read_hdf5_history(path, named_at, reading.columns), {}, reading.force_offset};
  }
  const Table table = read_table(path, named_at, reading.step);
  FitDataSet set{path, weight, HarmonicData{}, {table.step, false, {}, {}}, reading.force_offset};
  const bool amplitude = find_role(table, Role::amplitude, reading.columns) >= 0 || reading.amplitude || reading.strain_amplitude;
  if (amplitude && find_role(table, Role::frequency, reading.columns) >= 0) {
    set.data = harmonic_data_from_table(table, reading);
    if (set.harmonic().material) set.source = {table.step, true, reading.columns.area, reading.columns.height};
    if (reading.force_offset.given)
      std::get<HarmonicData>(set.data).notes.push_back(
          fmt::format("{}: force_offset has no effect on a harmonic table: its stiffness and phase do not depend on a constant force", path));
  } else if (find_role(table, Role::time, reading.columns) >= 0) {
    set.data = history_data_from_table(table, reading);
  } else {
    throw DataError(fmt::format(
        "{}cannot tell what this data is; a harmonic table needs 'amplitude', 'frequency' and 'stiffness'+'phase' or "
        "'storage'+'loss' columns, a history needs 'time', 'displacement' and 'force' (name unusual columns on the data line: "
        "columns = \"frequency = f, storage = E_stor\"); {}{}",
        header_error(table), header_columns(table), table.step.empty() ? "" : fmt::format(" (TRIOS step \"{}\")", lang::printable(table.step))));
  }
  return set;
}

DataReading reading_of(const lang::FitData& line) {
  DataReading reading;
  reading.columns = column_reading(line.columns);
  reading.columns.area = line.area;
  reading.columns.height = line.height;
  reading.step = line.step;
  reading.duplicates = line.duplicates;
  reading.force_offset = {line.force_offset.given, line.force_offset.free, line.force_offset.value};
  if (line.amplitude_is_strain) reading.strain_amplitude = line.amplitude;
  else reading.amplitude = line.amplitude;
  return reading;
}

}  // namespace rheo::runtime
