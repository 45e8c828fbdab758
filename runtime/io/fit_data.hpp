// Measurements a fit is scored against, one per file: a harmonic table (harmonic_data.hpp) or a
// time history (`time`, `displacement`, `force` columns, the network relaxed at the first sample, as in the static
// and quasi-static tests of thesis section 4.3). The kind is read from the header; a file that
// is neither is a DataError listing the columns each kind needs.
//
// A history in a CSV file is read as it streams, into arrays of doubles (stream_measured_history):
// a fit holds the measured history so, not as text or a table of cells, and simulates it at every
// evaluation without reading or copying it again. Harmonic tables (and histories the stream does
// not take) are read whole, at most lang::max_table_bytes of text.
#pragma once

#include "lang/limits.hpp"
#include "runtime/core/drive.hpp"
#include "runtime/io/harmonic_data.hpp"

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace rheo::runtime {

struct DrivePiece;  // history_stream.hpp

// The 1-based file line of each sample of a measured history (an HDF5 or MATLAB file's: the
// sample's index), held as runs of consecutive lines: memory by the runs (a CSV's comment and
// blank lines between data rows), not by the samples. The same rows in the same order are one
// representation, so equal rows compare equal.
class SampleRows {
 public:
  SampleRows() = default;
  SampleRows(std::initializer_list<int> rows);

  void push_back(int row);
  void append(const std::vector<int>& rows);
  void assign(std::size_t count, int row);  // COUNT samples on ROW (a run each where they repeat)
  void clear();
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  int operator[](std::size_t sample) const;  // std::out_of_range beyond size()
  int front() const { return (*this)[0]; }
  std::vector<int> all() const;  // every sample's row, in order
  std::size_t runs() const { return runs_.size(); }

  bool operator==(const SampleRows& other) const = default;
  friend bool operator==(const SampleRows& rows, const std::vector<int>& all) { return rows.all() == all; }

 private:
  struct Run {
    std::size_t first_sample;  // its rows: first_row, first_row + 1, ... from this sample on
    int first_row;
    bool operator==(const Run&) const = default;
  };
  std::vector<Run> runs_;
  std::size_t size_ = 0;
};

struct HistoryData {
  std::string path;
  Drive drive;                // the measured displacement; the network starts relaxed at its first sample
  std::vector<double> force;  // measured force at each drive sample [N]
  SampleRows rows;            // 1-based file line of each sample
  double force_scale = 1.0;   // max |F| [N]: residuals are relative to it

  // Appends the samples of PIECE and their forces FORCE [N] (one per sample), as a reader yields them.
  void append(const DrivePiece& piece, const std::vector<double>& piece_force);
  // force_scale := max |F| of the samples held.
  void set_force_scale();
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

// What a held sample of a measured history takes: time, displacement and force as doubles (its
// row is in a run of SampleRows).
inline constexpr std::size_t kHeldSampleBytes = 3 * sizeof(double);

HistoryData history_data_from_table(const Table& table);
HistoryData history_data_from_table(const Table& table, const DataReading& reading);
// NAMED_AT: where a .rheo file's `data` line names PATH (read_table). READING: how the line
// asks for it to be read.
FitDataSet read_fit_data(const std::string& path, double weight, const lang::SourceLocation* named_at = nullptr, const DataReading& reading = {});
// A measured history in the CSV file PATH read piece by piece (history_stream.hpp) into
// HistoryData's arrays, with no text held and no table of cells: the bound is on the samples
// held (MOST, kHeldSampleBytes each: 512 MiB of them by default), not on the file's bytes, a
// DataError when the file has more. Its faults are those history_data_from_table(read_table())
// gives, at the same file:row:col. nullopt for a file read_fit_data reads whole: not a regular
// file, a TRIOS step asked for, a header that is not a history's with a force (a harmonic table,
// none at all), a fault in the lines before its first data row, a file the stream does not take
// (NotStreamable).
std::optional<HistoryData> stream_measured_history(const std::string& path, const lang::SourceLocation* named_at, const DataReading& reading,
                                                   std::size_t most = lang::max_table_bytes / kHeldSampleBytes);
// The reading a checked data line asks for.
DataReading reading_of(const lang::FitData& line);

}  // namespace rheo::runtime
