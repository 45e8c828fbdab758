// Measured harmonic tables (thesis Table 4.5 grids): one row per (amplitude, frequency) with
// either stiffness + phase or storage + loss columns, units in the header
// (`amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]`). Converted to the internal
// system: amplitude mm, frequency Hz, stiffness N/mm, phase rad. Malformed input (missing
// column, negative or zero amplitude or frequency, non-positive stiffness, a phase outside
// (-90, 180] deg (beyond 90 deg: above a resonance), negative weight) is a DataError naming file:row:column. Points at the same
// (amplitude, frequency), relative 1e-9 (overlapping segments of a master curve), are averaged
// into one, with a note, or are an error under DataReading::duplicates = error. A
// phase <= 0 or >= 180 deg (noise on a nearly elastic or undamped point) is kept: fits leave its damping term out
// (objective.hpp, damping_residual).
// An optional `weight [-]` column weighs each point's residuals in a fit.
// Columns are found by role (column_roles.hpp); moduli and strains of material data become
// stiffness and displacement through the geometry a data line gives.
#pragma once

#include "lang/fit_settings.hpp"
#include "runtime/io/column_roles.hpp"
#include "runtime/io/history_csv.hpp"

#include <optional>
#include <string>
#include <vector>

namespace rheo::runtime {

// A constant offset of a measured history's force (a load cell's zero): measured force =
// network force + offset. A harmonic table's stiffness and phase do not depend on it.
struct ForceOffset {
  bool given = false;  // set on the data line
  bool free = false;   // fitted: the least-squares offset at every evaluation (fit/force_offset.hpp)
  double value = 0.0;  // N: the declared offset (not free)
};

// How a data line asks for its file to be read (from lang::FitData, checked there): which
// column is which and the specimen's geometry (column_roles.hpp), a TRIOS step
// (table_layout.hpp), an amplitude for a table without one.
struct DataReading {
  ColumnReading columns;
  std::string step;
  std::optional<double> amplitude;         // mm
  std::optional<double> strain_amplitude;  // a plain strain (0.001 for 0.1 %); needs columns.height
  lang::DuplicatePoints duplicates = lang::DuplicatePoints::average;
  ForceOffset force_offset{};
};

struct HarmonicData {
  std::string path;
  std::vector<double> amplitude;  // mm
  std::vector<double> frequency;  // Hz
  std::vector<double> stiffness;  // N/mm, K = |K*|
  std::vector<double> phase;      // rad
  std::vector<double> weight;     // per-point weight (optional column `weight [-]`, default 1)
  std::vector<double> preload;    // mm, per point: the mean displacement p (optional column `preload [mm]`, default 0)
  std::vector<int> rows;          // 1-based file line of each point
  // Where the values came from, for messages and reports: table columns (-1: from the data line).
  int amplitude_column = -1, frequency_column = -1, stiffness_column = -1, phase_column = -1;
  bool material = false;           // moduli or strains converted by the data line's geometry
  std::vector<std::string> notes;  // what reading did beyond the rows, "FILE:ROW: ..." (points averaged)
  std::size_t size() const { return amplitude.size(); }
};

HarmonicData harmonic_data_from_table(const Table& table);
HarmonicData harmonic_data_from_table(const Table& table, const DataReading& reading);
HarmonicData read_harmonic_data(const std::string& path);

}  // namespace rheo::runtime
