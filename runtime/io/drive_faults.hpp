// What drive_from_table (history_csv.hpp) refuses in a displacement history's rows, as
// messages both the whole-file and the streamed reader (history_stream.hpp) give, so that a
// fault reads the same whichever found it. Each message is a whole "file:row:col: error: ..."
// line.
#pragma once

#include "runtime/io/history_csv.hpp"

#include <string>

namespace rheo::runtime::drive_faults {

// The header lacks a time or a displacement column.
std::string missing_columns(const Table& table);
// The table has one data row, at ROW.
std::string too_few_rows(const std::string& path, int row);
// With start = rest: whether the first displacement U0 is rest, within 1e-9 of the largest
// |displacement| LARGEST of the history (any scale of the physical range); the fault at ROW:COLUMN.
bool starts_at_rest(double u0, double largest);
std::string not_at_rest(const std::string& path, int row, int column, double u0);
// Time T at ROW:COLUMN not after T_BEFORE at ROW_BEFORE.
std::string time_not_increasing(const std::string& path, int row, int column, double t, double t_before, int row_before);
// Whether a rig can drive displacement U [mm] (lang::max_amplitude); the fault at ROW:COLUMN.
bool drivable(double u);
std::string not_drivable(const std::string& path, int row, int column, double u);
// A measured history's (fit_data.hpp): the header lacks a force column; every force is zero
// (the first row's force cell at ROW:COLUMN).
std::string missing_force(const Table& table);
std::string zero_force(const std::string& path, int row, int column);

}  // namespace rheo::runtime::drive_faults
