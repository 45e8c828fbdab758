// HDF5 files written and read in tests with the HDF5 C API directly (not through rheo's
// readers and writers): the independent path the HDF5 tests compare against.
#pragma once

#include <doctest/doctest.h>
#include <hdf5.h>

#include <optional>
#include <string>
#include <vector>

namespace rheo::test::hdf5 {

struct DatasetSpec {
  std::string path{};            // groups on the way are created
  std::vector<double> values{};  // written as TYPE (converted by HDF5)
  hid_t type = H5T_IEEE_F64LE;
  std::optional<std::string> units{};  // the "units" attribute; none when nullopt
  bool chunked = false;                // else contiguous
  bool column = false;                 // an N x 1 matrix instead of a vector
  bool fixed_string = false;           // units as a fixed-length string (else variable-length)
};

inline void write_units(hid_t object, const std::string& units, bool fixed) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  REQUIRE(H5Tset_size(type, fixed ? units.size() : H5T_VARIABLE) >= 0);
  if (fixed) REQUIRE(H5Tset_strpad(type, H5T_STR_NULLPAD) >= 0);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attribute = H5Acreate2(object, "units", type, space, H5P_DEFAULT, H5P_DEFAULT);
  REQUIRE(attribute >= 0);
  const char* text = units.c_str();
  REQUIRE(H5Awrite(attribute, type, fixed ? static_cast<const void*>(text) : static_cast<const void*>(&text)) >= 0);
  H5Aclose(attribute), H5Sclose(space), H5Tclose(type);
}

inline void write_file(const std::string& file, const std::vector<DatasetSpec>& datasets) {
  const hid_t f = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  REQUIRE(f >= 0);
  const hid_t links = H5Pcreate(H5P_LINK_CREATE);
  H5Pset_create_intermediate_group(links, 1);
  for (const auto& d : datasets) {
    const hsize_t dims[2] = {d.values.size(), 1};
    const hid_t space = H5Screate_simple(d.column ? 2 : 1, dims, nullptr);
    const hid_t layout = H5Pcreate(H5P_DATASET_CREATE);
    const hsize_t chunk[2] = {7, 1};  // a chunk that does not divide the pieces read
    if (d.chunked) REQUIRE(H5Pset_chunk(layout, d.column ? 2 : 1, chunk) >= 0);
    const hid_t dataset = H5Dcreate2(f, d.path.c_str(), d.type, space, links, layout, H5P_DEFAULT);
    REQUIRE(dataset >= 0);
    if (!d.values.empty()) REQUIRE(H5Dwrite(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.values.data()) >= 0);
    if (d.units) write_units(dataset, *d.units, d.fixed_string);
    H5Dclose(dataset), H5Pclose(layout), H5Sclose(space);
  }
  H5Pclose(links);
  REQUIRE(H5Fclose(f) >= 0);
}

// The doubles of dataset PATH of FILE, whole.
inline std::vector<double> read_dataset(const std::string& file, const std::string& path) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(f >= 0);
  const hid_t dataset = H5Dopen2(f, path.c_str(), H5P_DEFAULT);
  REQUIRE_MESSAGE(dataset >= 0, path);
  const hid_t space = H5Dget_space(dataset);
  std::vector<double> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  REQUIRE(H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) >= 0);
  H5Sclose(space), H5Dclose(dataset), H5Fclose(f);
  return values;
}

// The string attribute NAME of the object at PATH (a variable-length string, as rheo writes it).
inline std::string read_string_attribute(const std::string& file, const std::string& path, const char* name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(f >= 0);
  const hid_t attribute = H5Aopen_by_name(f, path.c_str(), name, H5P_DEFAULT, H5P_DEFAULT);
  REQUIRE_MESSAGE(attribute >= 0, path << " " << name);
  const hid_t type = H5Aget_type(attribute);
  REQUIRE(H5Tis_variable_str(type) > 0);
  char* value = nullptr;
  REQUIRE(H5Aread(attribute, type, &value) >= 0);
  std::string text = value ? value : "";
  H5free_memory(value);
  H5Tclose(type), H5Aclose(attribute), H5Fclose(f);
  return text;
}

// The layout of dataset PATH: H5D_CHUNKED, H5D_CONTIGUOUS, ...
inline H5D_layout_t layout_of(const std::string& file, const std::string& path) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t dataset = H5Dopen2(f, path.c_str(), H5P_DEFAULT);
  const hid_t plist = H5Dget_create_plist(dataset);
  const H5D_layout_t layout = H5Pget_layout(plist);
  H5Pclose(plist), H5Dclose(dataset), H5Fclose(f);
  return layout;
}

}  // namespace rheo::test::hdf5
