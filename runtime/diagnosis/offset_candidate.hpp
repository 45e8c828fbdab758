// The candidate of the effect `offset` (trial.hpp Shape::force_offset): not an element but a
// constant c in the measured force of every history whose offset is not fitted already,
// m = F + c (fit/force_offset.hpp: one unknown per data line, solved exactly at every
// evaluation), written as `force_offset = free` on those data lines.
#pragma once

#include "lang/fitted_source.hpp"
#include "lang/model.hpp"
#include "runtime/diagnosis/diagnose.hpp"
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

// BEFORE (the model as fitted) refitted to FREED_DATA (its histories' offsets made free): every
// free parameter by one local search (refit.hpp local_search) within the budget of SETTINGS; the
// offset adds no shape parameter for a first stage to place.
FitResult refit_with_offsets(const FitResult& before, const std::vector<FitDataSet>& freed_data, const DiagnoseSettings& settings);

// The data lines of PROGRAM's fit block BLOCK, where it has one per data set (COUNT); else empty.
std::vector<lang::FitData> fit_block_lines(const lang::Program& program, int block, std::size_t count);

// The refined file's header for the effect offset: the gap's fall (GAP_NAME, BEFORE -> AFTER),
// the fitted values, and where `force_offset = free` is stated (on FREED data lines, or how).
std::vector<std::string> offset_header(const OffsetText& text, std::size_t freed, const std::string& gap_name, double before, double after);

}  // namespace rheo::runtime::diagnosis
