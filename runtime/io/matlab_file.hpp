// MATLAB .mat files as histories (docs/data-formats.md, "MATLAB files"). A v7.3 MAT-file
// (`save -v7.3`) is an HDF5 file behind a 512-byte user block whose text starts
// "MATLAB 7.3 MAT-file": each variable is a dataset of the root group, a struct a group whose
// fields are datasets in it, each with a MATLAB_class attribute ("double", "single", "int16",
// "char", "logical", "cell", "struct", ...), its dimensions reversed (MATLAB stores column-major:
// a 1 x N row vector is an N x 1 dataset, an N x 1 column a 1 x N one). HDF5 reads it as any
// HDF5 file (hdf5_history.hpp); this says what is MATLAB's own: which files are .mat, why an
// older one cannot be read, and which variables hold numbers.
//
// Earlier MAT-files (v4, and v5/v7, the default of `save`, whose 128-byte header starts
// "MATLAB 5.0 MAT-file") are not HDF5: refused with what to do (re-save with -v7.3, or export
// CSV). Of MATLAB's classes, the numeric ones (double, single, int8 ... uint64) are read,
// converted to doubles by HDF5; char (text, stored as uint16), logical (uint8), cell, struct,
// sparse, complex and empty arrays, and objects (string, datetime, table, ...) are refused
// naming the variable: their integers are not measurements.
#pragma once

#include <hdf5.h>

#include <optional>
#include <string>
#include <string_view>

namespace rheo::runtime {

// Whether PATH names a MATLAB file: it ends in .mat (any case).
bool is_matlab_name(const std::string& path);

// Which MATLAB header START (a file's first bytes) begins with.
enum class MatHeader { none, v5, v73 };
MatHeader matlab_header(std::string_view start);

// The DataError for FILE, named .mat, that is not an HDF5 file: a v5/v7 MAT-file (re-save it
// with -v7.3, or export CSV), or another file.
[[noreturn]] void refuse_non_hdf5_matlab(const std::string& file);

// A `columns` path in a .mat FILE written as MATLAB writes a struct's field ("rig.t") as the
// HDF5 path ("rig/t"); any other path as it is. MATLAB's names hold no '.', HDF5's may: only
// for .mat files.
std::string matlab_field_path(const std::string& file, const std::string& path);

// OBJECT's MATLAB_class attribute ("double", "struct", ...); nullopt for an object MATLAB did
// not write. PATH names OBJECT in FILE's messages.
std::optional<std::string> matlab_class(hid_t object, const std::string& file, const std::string& path);

// Checks that DATASET (at PATH in FILE, read for ROLE_TEXT), if MATLAB wrote it, holds real
// numbers HDF5 can convert to doubles: a DataError naming the variable and what to do for text,
// logical values, a cell array, complex or empty arrays and objects. Nothing checked for a
// dataset without a MATLAB_class.
void check_matlab_dataset(hid_t dataset, const std::string& file, const std::string& path, const std::string& role_text);

// For GROUP (at PATH in FILE) named where ROLE_TEXT's dataset is expected: the DataError for a
// MATLAB sparse matrix (save it full) or struct (name a field: HOLDS lists its fields); returns
// for a group MATLAB did not write.
void refuse_matlab_group(hid_t group, const std::string& file, const std::string& path, const std::string& role_text, const std::string& holds);

}  // namespace rheo::runtime
