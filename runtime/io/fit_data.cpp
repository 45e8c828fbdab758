#include "runtime/io/fit_data.hpp"

#include "lang/limits.hpp"
#include "lang/text_encoding.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/io/drive_faults.hpp"
#include "runtime/io/hdf5_history.hpp"
#include "runtime/io/history_stream.hpp"
#include "runtime/io/matlab_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <optional>
#include <stdexcept>

namespace rheo::runtime {

SampleRows::SampleRows(std::initializer_list<int> rows) {
  for (int row : rows) push_back(row);
}

void SampleRows::push_back(int row) {
  if (runs_.empty() || static_cast<long long>(row) != runs_.back().first_row + static_cast<long long>(size_ - runs_.back().first_sample))
    runs_.push_back({size_, row});
  ++size_;
}

void SampleRows::append(const std::vector<int>& rows) {
  for (int row : rows) push_back(row);
}

void SampleRows::assign(std::size_t count, int row) {
  clear();
  for (std::size_t k = 0; k < count; ++k) push_back(row);
}

void SampleRows::clear() {
  runs_.clear();
  size_ = 0;
}

int SampleRows::operator[](std::size_t sample) const {
  if (sample >= size_) throw std::out_of_range(fmt::format("SampleRows: sample {} of {}", sample, size_));
  const auto run = std::prev(std::upper_bound(runs_.begin(), runs_.end(), sample, [](std::size_t k, const Run& r) { return k < r.first_sample; }));
  return run->first_row + static_cast<int>(sample - run->first_sample);
}

std::vector<int> SampleRows::all() const {
  std::vector<int> out;
  out.reserve(size_);
  for (std::size_t r = 0; r < runs_.size(); ++r) {
    const std::size_t end = r + 1 < runs_.size() ? runs_[r + 1].first_sample : size_;
    for (std::size_t k = runs_[r].first_sample; k < end; ++k) out.push_back(runs_[r].first_row + static_cast<int>(k - runs_[r].first_sample));
  }
  return out;
}

void HistoryData::append(const DrivePiece& piece, const std::vector<double>& piece_force) {
  drive.time.insert(drive.time.end(), piece.time.begin(), piece.time.end());
  drive.displacement.insert(drive.displacement.end(), piece.displacement.begin(), piece.displacement.end());
  force.insert(force.end(), piece_force.begin(), piece_force.end());
  rows.append(piece.rows);
}

void HistoryData::set_force_scale() {
  force_scale = 0.0;
  for (double v : force) force_scale = std::max(force_scale, std::abs(v));
}

namespace {

// Whether TABLE's header makes it a harmonic table: amplitude (or one on the data line) and
// frequency columns.
bool harmonic_header(const Table& table, const DataReading& reading) {
  const bool amplitude = find_role(table, Role::amplitude, reading.columns) >= 0 || reading.amplitude || reading.strain_amplitude;
  return amplitude && find_role(table, Role::frequency, reading.columns) >= 0;
}

}  // namespace

std::optional<HistoryData> stream_measured_history(const std::string& path, const lang::SourceLocation* named_at, const DataReading& reading,
                                                   std::size_t most) {
  std::error_code error;
  if (!reading.step.empty() || !std::filesystem::is_regular_file(path, error)) return std::nullopt;
  try {
    HistoryStream stream(path, named_at, false);
    stream.read_columns(reading.columns);
    const Table* head = stream.header();
    if (!head || head->rows.empty()) return std::nullopt;
    try {
      if (harmonic_header(*head, reading) || find_role(*head, Role::time, reading.columns) < 0 || find_role(*head, Role::force, reading.columns) < 0)
        return std::nullopt;
    } catch (const DataError&) {  // a column the data line names that the header lacks: said where whole-file reading says it
      return std::nullopt;
    }
    stream.read_force();
    HistoryData h;
    h.path = path;
    DrivePiece piece;
    std::vector<double> force;
    while (stream.next(piece, &force)) {
      if (h.force.size() + force.size() > most)
        throw DataError(
            fmt::format("{}: error: the history has more than {} samples, the most a fit or report holds ({} MiB at {} bytes a "
                        "sample); fit a part of it, or resample it",
                        lang::printable(path), most, lang::max_table_bytes >> 20, kHeldSampleBytes));
      if (h.force.empty()) {  // room for the whole file at the first piece's bytes a row: no copies as it grows
        const double rows = static_cast<double>(stream.file_size()) * static_cast<double>(force.size()) /
                            static_cast<double>(std::max<std::uint64_t>(stream.bytes_read(), 1));
        const auto n = static_cast<std::size_t>(std::min(1.02 * rows + 1024.0, static_cast<double>(most)));
        h.drive.time.reserve(n), h.drive.displacement.reserve(n), h.force.reserve(n);
      }
      h.append(piece, force);
    }
    h.set_force_scale();
    return h;
  } catch (const NotStreamable&) {
    return std::nullopt;
  }
}

HistoryData history_data_from_table(const Table& table) { return history_data_from_table(table, DataReading{}); }

HistoryData history_data_from_table(const Table& table, const DataReading& reading) {
  const int f = find_role(table, Role::force, reading.columns);
  if (f < 0) throw DataError(drive_faults::missing_force(table));
  HistoryData h;
  h.path = table.path;
  h.drive = drive_from_table(table, reading.columns);
  h.force = role_values(table, f, Role::force, reading.columns);
  h.rows.append(table.rows);
  h.set_force_scale();
  if (!(h.force_scale > 0.0)) throw DataError(drive_faults::zero_force(table.path, table.rows.front(), table.cell_column(0, f)));
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
  if (auto history = stream_measured_history(path, named_at, reading)) return {path, weight, std::move(*history), {}, reading.force_offset};
  const Table table = read_table(path, named_at, reading.step);
  FitDataSet set{path, weight, HarmonicData{}, {table.step, false, {}, {}}, reading.force_offset};
  if (harmonic_header(table, reading)) {
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
