// Measured harmonic tables (thesis Table 4.5 grids): one row per (amplitude, frequency) with
// either stiffness + phase or storage + loss columns, units in the header
// (`amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]`). Converted to the internal
// system: amplitude mm, frequency Hz, stiffness N/mm, phase rad. Malformed input (missing
// column, negative or zero amplitude or frequency, non-positive stiffness, a phase outside
// (-90, 90] deg, duplicate point, negative weight) is a DataError naming file:row:column. A
// phase <= 0 (noise on a nearly elastic point) is kept: fits leave its damping term out
// (objective.hpp, damping_residual).
// An optional `weight [-]` column weighs each point's residuals in a fit.
#pragma once

#include "runtime/io/history_csv.hpp"

#include <string>
#include <vector>

namespace rheo::runtime {

struct HarmonicData {
  std::string path;
  std::vector<double> amplitude;  // mm
  std::vector<double> frequency;  // Hz
  std::vector<double> stiffness;  // N/mm, K = |K*|
  std::vector<double> phase;      // rad
  std::vector<double> weight;     // per-point weight (optional column `weight [-]`, default 1)
  std::vector<int> rows;          // 1-based file line of each point
  std::size_t size() const { return amplitude.size(); }
};

HarmonicData harmonic_data_from_table(const Table& table);
HarmonicData read_harmonic_data(const std::string& path);

}  // namespace rheo::runtime
