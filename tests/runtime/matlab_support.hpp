// MATLAB v7.3 .mat files written in tests with the HDF5 C API as MATLAB writes them (MATLAB is
// not available here): an HDF5 file behind a 512-byte user block holding MATLAB's 128-byte
// header ("MATLAB 7.3 MAT-file, ..." then version 0x0200 and "IM"), each variable a dataset of
// the root group (a struct's fields datasets in a group) with a MATLAB_class attribute, its
// dimensions reversed (a 1 x N row vector is an N x 1 dataset, an N x 1 column 1 x N), char as
// uint16 with MATLAB_int_decode = 2, logical as uint8, a cell as object references into #refs#,
// an empty array as its uint64 dimensions with MATLAB_empty = 1, complex as a {real, imag}
// compound, sparse as a group with MATLAB_sparse.
#pragma once

#include <doctest/doctest.h>
#include <hdf5.h>

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace rheo::test::matlab {

enum class Kind { numeric, text, logical, cell, empty, complex, sparse };

struct Variable {
  std::string path{};            // "/t", or "/rig/t" for field t of struct rig (groups made structs)
  std::vector<double> values{};  // written as TYPE (converted by HDF5)
  std::string matlab_class = "double";
  hid_t type = H5T_IEEE_F64LE;
  bool row = true;  // a 1 x N row vector (dataset N x 1), else an N x 1 column (dataset 1 x N)
  Kind kind = Kind::numeric;
  std::optional<std::string> units{};  // a "units" attribute (h5writeatt), which MATLAB does not write
};

inline void write_class(hid_t object, const std::string& matlab_class) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  REQUIRE(H5Tset_size(type, matlab_class.size()) >= 0);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attribute = H5Acreate2(object, "MATLAB_class", type, space, H5P_DEFAULT, H5P_DEFAULT);
  REQUIRE(attribute >= 0);
  REQUIRE(H5Awrite(attribute, type, matlab_class.c_str()) >= 0);
  H5Aclose(attribute), H5Sclose(space), H5Tclose(type);
}

inline void write_number_attribute(hid_t object, const char* name, hid_t type, unsigned value) {
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attribute = H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  REQUIRE(attribute >= 0);
  REQUIRE(H5Awrite(attribute, H5T_NATIVE_UINT, &value) >= 0);
  H5Aclose(attribute), H5Sclose(space);
}

inline void write_units(hid_t object, const std::string& units) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  REQUIRE(H5Tset_size(type, H5T_VARIABLE) >= 0);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attribute = H5Acreate2(object, "units", type, space, H5P_DEFAULT, H5P_DEFAULT);
  const char* text = units.c_str();
  REQUIRE(H5Awrite(attribute, type, &text) >= 0);
  H5Aclose(attribute), H5Sclose(space), H5Tclose(type);
}

// The group at PATH's parent, made a struct (MATLAB_class "struct") on the way.
inline hid_t parent_of(hid_t file, const std::string& path) {
  const auto slash = path.rfind('/');
  if (slash == 0) return H5Gopen2(file, "/", H5P_DEFAULT);
  const std::string group = path.substr(0, slash);
  if (H5Lexists(file, group.c_str(), H5P_DEFAULT) > 0) return H5Gopen2(file, group.c_str(), H5P_DEFAULT);
  const hid_t made = H5Gcreate2(file, group.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  REQUIRE(made >= 0);
  write_class(made, "struct");
  return made;
}

inline void write_variable(hid_t file, const Variable& v) {
  const hid_t parent = parent_of(file, v.path);
  const std::string name = v.path.substr(v.path.rfind('/') + 1);
  const hsize_t n = v.values.size();
  const hsize_t dims[2] = {v.row ? n : 1, v.row ? 1 : n};
  hid_t object = -1;
  if (v.kind == Kind::sparse) {
    object = H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    write_class(object, v.matlab_class);
    write_number_attribute(object, "MATLAB_sparse", H5T_STD_U64LE, static_cast<unsigned>(n));
    H5Gclose(object), H5Gclose(parent);
    return;
  }
  if (v.kind == Kind::empty) {  // MATLAB writes an empty array's dimensions, with MATLAB_empty
    const hsize_t two = 2;
    const hid_t space = H5Screate_simple(1, &two, nullptr);
    object = H5Dcreate2(parent, name.c_str(), H5T_STD_U64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const unsigned long long zeros[2] = {0, 0};
    REQUIRE(H5Dwrite(object, H5T_NATIVE_ULLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, zeros) >= 0);
    write_number_attribute(object, "MATLAB_empty", H5T_STD_U8LE, 1);
    H5Sclose(space);
  } else if (v.kind == Kind::complex) {
    const hid_t type = H5Tcreate(H5T_COMPOUND, 16);
    H5Tinsert(type, "real", 0, H5T_IEEE_F64LE), H5Tinsert(type, "imag", 8, H5T_IEEE_F64LE);
    const hid_t space = H5Screate_simple(2, dims, nullptr);
    object = H5Dcreate2(parent, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    std::vector<double> pairs;
    for (double x : v.values) pairs.push_back(x), pairs.push_back(0.5);
    REQUIRE(H5Dwrite(object, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, pairs.data()) >= 0);
    H5Sclose(space), H5Tclose(type);
  } else if (v.kind == Kind::cell) {  // each cell a double array in #refs#
    const hid_t refs = H5Lexists(file, "/#refs#", H5P_DEFAULT) > 0 ? H5Gopen2(file, "/#refs#", H5P_DEFAULT)
                                                                   : H5Gcreate2(file, "/#refs#", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    std::vector<hobj_ref_t> references(v.values.size());
    for (std::size_t k = 0; k < v.values.size(); ++k) {
      const std::string cell = "/#refs#/" + name + std::to_string(k);
      const hsize_t one[2] = {1, 1};
      const hid_t space = H5Screate_simple(2, one, nullptr);
      const hid_t d = H5Dcreate2(file, cell.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      REQUIRE(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v.values[k]) >= 0);
      write_class(d, "double");
      H5Dclose(d), H5Sclose(space);
      REQUIRE(H5Rcreate(&references[k], file, cell.c_str(), H5R_OBJECT, -1) >= 0);
    }
    const hid_t space = H5Screate_simple(2, dims, nullptr);
    object = H5Dcreate2(parent, name.c_str(), H5T_STD_REF_OBJ, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    REQUIRE(H5Dwrite(object, H5T_STD_REF_OBJ, H5S_ALL, H5S_ALL, H5P_DEFAULT, references.data()) >= 0);
    H5Sclose(space), H5Gclose(refs);
  } else {
    const hid_t type = v.kind == Kind::text ? H5T_STD_U16LE : v.kind == Kind::logical ? H5T_STD_U8LE : v.type;
    const hid_t space = H5Screate_simple(2, dims, nullptr);
    object = H5Dcreate2(parent, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    REQUIRE(object >= 0);
    if (!v.values.empty()) REQUIRE(H5Dwrite(object, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.values.data()) >= 0);
    if (v.kind == Kind::text) write_number_attribute(object, "MATLAB_int_decode", H5T_STD_I32LE, 2);
    H5Sclose(space);
  }
  REQUIRE(object >= 0);
  write_class(object, v.kind == Kind::text ? "char" : v.kind == Kind::logical ? "logical" : v.kind == Kind::cell ? "cell" : v.matlab_class);
  if (v.units) write_units(object, *v.units);
  H5Dclose(object), H5Gclose(parent);
}

// MATLAB's 128-byte header: 116 bytes of text, 8 of subsystem offset, version 0x0200, "IM".
inline std::string mat_header(const std::string& version) {
  std::string header = "MATLAB " + version + " MAT-file, Platform: GLNXA64, Created on: Fri Nov 27 08:00:00 2026" +
                       (version == "7.3" ? " HDF5 schema 1.00 ." : "");
  header.resize(116, ' ');
  header += std::string(8, '\0');
  header += std::string("\x00\x02", 2) + "IM";
  return header;
}

// A v7.3 MAT-file holding VARIABLES.
inline void write_mat(const std::string& file, const std::vector<Variable>& variables) {
  const hid_t create = H5Pcreate(H5P_FILE_CREATE);
  REQUIRE(H5Pset_userblock(create, 512) >= 0);
  const hid_t f = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, create, H5P_DEFAULT);
  REQUIRE(f >= 0);
  for (const auto& v : variables) write_variable(f, v);
  REQUIRE(H5Fclose(f) >= 0);
  H5Pclose(create);
  std::FILE* out = std::fopen(file.c_str(), "r+b");
  REQUIRE(out);
  const std::string header = mat_header("7.3");
  REQUIRE(std::fwrite(header.data(), 1, header.size(), out) == header.size());
  std::fclose(out);
}

// A v5 MAT-file's start (its header, then a data element's tag), as `save` writes by default.
inline void write_v5_mat(const std::string& file) {
  std::FILE* out = std::fopen(file.c_str(), "wb");
  REQUIRE(out);
  const std::string bytes = mat_header("5.0") + std::string("\x0e\x00\x00\x00\x38\x00\x00\x00", 8);
  REQUIRE(std::fwrite(bytes.data(), 1, bytes.size(), out) == bytes.size());
  std::fclose(out);
}

}  // namespace rheo::test::matlab
