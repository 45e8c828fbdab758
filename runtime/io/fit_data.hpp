// Measurements a fit is scored against, one per file: a harmonic table (harmonic_data.hpp) or a
// time history (`time`, `displacement`, `force` columns, the network relaxed at the first sample, as in the static
// and quasi-static tests of thesis section 4.3). The kind is read from the header; a file that
// is neither is a DataError listing the columns each kind needs.
#pragma once

#include "runtime/core/drive.hpp"
#include "runtime/io/harmonic_data.hpp"

#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace rheo::runtime {

struct HistoryData {
  std::string path;
  Drive drive;                // the measured displacement; the network starts relaxed at its first sample
  std::vector<double> force;  // measured force at each drive sample [N]
  std::vector<int> rows;      // 1-based file line of each sample
  double force_scale = 1.0;   // max |F| [N]: residuals are relative to it
};

// Where a data set's values came from beyond its path, for reports.
struct DataSource {
  std::string step;                    // the TRIOS step read; empty for a plain table
  bool material = false;               // moduli or strains turned into stiffness and displacement
  std::optional<double> area, height;  // mm^2, mm: the geometry that did it
};

struct FitDataSet {
  std::string path;
  double weight = 1.0;  // multiplies this file's mean squared residual in the objective
  std::variant<HarmonicData, HistoryData> data;
  DataSource source{};
  ForceOffset force_offset{};  // histories only (a harmonic table's reading notes that it has no effect)

  bool is_harmonic() const { return std::holds_alternative<HarmonicData>(data); }
  const HarmonicData& harmonic() const { return std::get<HarmonicData>(data); }
  const HistoryData& history() const { return std::get<HistoryData>(data); }
};

HistoryData history_data_from_table(const Table& table);
HistoryData history_data_from_table(const Table& table, const DataReading& reading);
// NAMED_AT: where a .rheo file's `data` line names PATH (read_table). READING: how the line
// asks for it to be read.
FitDataSet read_fit_data(const std::string& path, double weight, const lang::SourceLocation* named_at = nullptr, const DataReading& reading = {});
// The reading a checked data line asks for.
DataReading reading_of(const lang::FitData& line);

}  // namespace rheo::runtime
