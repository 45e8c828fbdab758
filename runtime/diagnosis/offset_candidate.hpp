// The candidate of the effect `offset` (trial.hpp Shape::force_offset): not an element but a
// constant c in the measured force of every history whose offset is not fitted already,
// m = F + c (fit/force_offset.hpp: one unknown per data line, solved exactly at every
// evaluation), written as `force_offset = free` on those data lines.
#pragma once

#include "lang/fitted_source.hpp"
#include "lang/model.hpp"
#include "runtime/fit/fit.hpp"

#include <string>
#include <vector>

namespace rheo::runtime::diagnosis {

// The indices of DATA's histories whose force offset is not free (none given, or declared).
std::vector<std::size_t> fixed_offsets(const std::vector<FitDataSet>& data);

// DATA with the force offsets of FREED made free.
std::vector<FitDataSet> with_free_offsets(const std::vector<FitDataSet>& data, const std::vector<std::size_t>& freed);

// How the refined file states the freed offsets. LINES: the data lines the data were read from
// (one per data set, in FILE's text; empty when they came from elsewhere). A line's declared
// offset becomes `free`; a line without one gets `, force_offset = free` after its last setting.
struct OffsetText {
  std::vector<lang::FittedSetting> edits;  // on FILE's text (lang::write_fitted_source)
  std::vector<std::string> statement;      // the data lines as written, or the --data option that states them
  std::string summary;                     // "data rig.csv: force_offset = -650.2 N", the fitted values
};
OffsetText offset_text(const std::string& text, const std::string& file, const std::vector<lang::FitData>& lines,
                       const std::vector<std::size_t>& freed, const FitResult& refit);

}  // namespace rheo::runtime::diagnosis
