// The quantities readers take from a table (its roles) and the header columns that give them.
// A role is found by the column a data line names for it (`columns = "frequency = f"`), else by
// its usual names, case-insensitively ("Storage Modulus", "E'", "Oscillation strain", ...;
// docs/data-formats.md lists them); of several candidates the first whose unit suits the role.
//
// Material data (moduli over strain, as rheometers and DMA report them) become the component's
// terms through the specimen's geometry: a modulus column (Pa, kPa, MPa, GPa, N/mm^2) gives
// stiffness K = E A / h [N/mm] with A the loaded area [mm^2] and h the height [mm]; a strain
// column (%, -, mm/mm) gives displacement u = eps h [mm].
#pragma once

#include "runtime/io/history_csv.hpp"

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rheo::runtime {

enum class Role { time, displacement, force, amplitude, frequency, stiffness, phase, storage, loss, weight, preload };

std::string_view role_name(Role role);
std::optional<Role> role_named(std::string_view name);

// How a data line asks for a table to be read.
struct ColumnReading {
  std::vector<std::pair<Role, std::string>> columns;  // a header name for a role, as the user wrote it
  std::optional<double> area;                         // mm^2
  std::optional<double> height;                       // mm
};

// ROLE's quantity in the component's terms, the kind of unit it needs ("time (s)") and an
// example of one ("s"), for readers that check units themselves (hdf5_history.hpp).
lang::Dimension role_dimension(Role role);
const char* role_unit_kind(Role role);
const char* role_unit_example(Role role);
// ROLE's usual names, as messages list them: "time, t, test time, elapsed time".
std::string role_usual_names(Role role);

// The ROLE = NAME pairs of a `columns` setting, checked by the language (lang/fit_schema.hpp).
ColumnReading column_reading(const std::vector<lang::ColumnName>& columns);

// The column giving ROLE, or -1. A column READING names that the header lacks is a DataError
// at the header listing its columns.
int find_role(const Table& table, Role role, const ColumnReading& reading);
// Whether column C's unit is one ROLE can be read in (its values may still be faulty).
bool role_suits(const Table& table, int c, Role role);
// Column C read as ROLE, in internal units; DataError at the fault (a cell that is not a number,
// a unit missing, unknown or of another kind, geometry missing for material data).
std::vector<double> role_values(const Table& table, int c, Role role, const ColumnReading& reading);
// Both; a table without the column is a DataError at the header: "WHAT need a column 'role'
// HINT; add it (the header has: ...)".
std::vector<double> need_role(const Table& table, Role role, const ColumnReading& reading, const std::string& what, const std::string& hint);

// Whether column C holds material data (a modulus or a strain) that READING's geometry converted.
bool is_material(const Table& table, int c);

}  // namespace rheo::runtime
