// Where an HDF5 file holds a history's quantities (docs/data-formats.md, "HDF5 files"): for each
// role the dataset a reading's `columns` names (a path from the root, checked group by group, an
// optional "[unit]" after it) or, where it names none, the default layout's (the first dataset of
// the root group named as the role's usual names, column_roles.hpp, whose unit suits it); the
// dataset checked to hold numbers (any floating-point or integer type) as a vector (rank 1, N x 1
// or 1 x N), and its unit (the one on the line, else its "units" string attribute) checked to
// be of the role's kind. Each fault is a DataError naming the file and the dataset, with what
// to do (hdf5_history.hpp lists them).
#pragma once

#include "runtime/io/column_roles.hpp"
#include "runtime/io/hdf5_owners.hpp"

#include <string>
#include <vector>

namespace rheo::runtime {

// A role's dataset, open.
struct Hdf5Column {
  Role role = Role::time;
  std::string path;  // absolute: "/rig/t"
  hdf5::Dataset dataset;
  hdf5::Dataspace space;  // the file's; readers select hyperslabs in it
  int axis = 0;           // the dimension the samples run along
  unsigned long long length = 0;
  double scale = 1.0;  // internal unit per unit of the dataset
};

// The datasets of ROLES, in that order, in FILE (open; FILE_NAME for messages) as READING names them.
std::vector<Hdf5Column> hdf5_columns(hid_t file, const std::string& file_name, const std::vector<Role>& roles, const ColumnReading& reading);

}  // namespace rheo::runtime
