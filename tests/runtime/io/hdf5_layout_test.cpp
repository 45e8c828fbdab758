// hdf5_columns (hdf5_layout.hpp) against files written here with the HDF5 C API (hdf5_support.hpp):
// which dataset each role gets (the default layout's by usual name and suitable unit, or the path a
// reading names, through groups, with an optional "[unit]"), its axis and length as a vector, its
// scale to internal units (s, mm, N), and each fault a DataError naming the file and the dataset
// with what to do. The reader's use of it is tested in hdf5_history_test.cpp.
#include "runtime/io/hdf5_layout.hpp"

#include "hdf5_support.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/io/hdf5_owners.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <filesystem>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

namespace hdf5_layout_test {

using namespace rheo::runtime;
namespace fs = std::filesystem;
using rheo::test::hdf5::DatasetSpec;
using rheo::test::hdf5::write_file;
using rheo::test::hdf5::write_units;

namespace {

fs::path scratch() {
  const auto dir = fs::temp_directory_path() / fmt::format("rheo-hdf5-layout-{}", ::getpid());
  fs::create_directories(dir);
  return dir;
}

std::string written(const std::string& name, const std::vector<DatasetSpec>& specs) {
  const auto file = (scratch() / name).string();
  write_file(file, specs);
  return file;
}

// Adds to FILE a dataset PATH of TYPE with DIMS (no values written; HDF5 fills them), with a
// "units" attribute UNITS when not empty.
void add_dataset(const std::string& file, const char* path, hid_t type, const std::vector<hsize_t>& dims, const std::string& units = "") {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  REQUIRE(f >= 0);
  const hid_t space = dims.empty() ? H5Screate(H5S_SCALAR) : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t dataset = H5Dcreate2(f, path, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  REQUIRE(dataset >= 0);
  if (!units.empty()) write_units(dataset, units, false);
  H5Dclose(dataset), H5Sclose(space);
  REQUIRE(H5Fclose(f) >= 0);
}

ColumnReading named(std::vector<std::pair<Role, std::string>> columns) { return ColumnReading{std::move(columns), {}, {}}; }

const std::vector<Role> kDrive{Role::time, Role::displacement};
const std::vector<Role> kMeasured{Role::time, Role::displacement, Role::force};

// Opens FILE with the project's owner and hands its columns to CHECK (the file stays open while
// the columns are looked at).
template <class Check>
void with_columns(const std::string& file, const std::vector<Role>& roles, const ColumnReading& reading, Check check) {
  hdf5::library();
  const hdf5::File f(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), file, "H5Fopen", "the file");
  const std::vector<Hdf5Column> columns = hdf5_columns(f.get(), file, roles, reading);
  REQUIRE(columns.size() == roles.size());
  for (std::size_t i = 0; i < roles.size(); ++i) CHECK(columns[i].role == roles[i]);
  check(columns);
}

std::string error_of(const std::string& file, const std::vector<Role>& roles, const ColumnReading& reading = {}) {
  try {
    with_columns(file, roles, reading, [](const std::vector<Hdf5Column>&) {});
  } catch (const DataError& e) {
    return e.what();
  }
  return "";
}

// The number of points COLUMN's dataspace holds.
long long points(const Hdf5Column& column) { return H5Sget_simple_extent_npoints(column.space.get()); }

doctest::Approx exactly(double value) { return doctest::Approx(value).epsilon(1e-14).scale(0.0); }

const std::vector<double> kSix{0.0, 1.0, 2.0, 3.0, 4.0, 5.0};

}  // namespace

TEST_CASE("the default layout: the root's datasets named as each role's usual names, in internal units") {
  const auto file = written("default.h5", {{"/notes", kSix, H5T_IEEE_F64LE, "mm"},
                                           {"/time", kSix, H5T_IEEE_F64LE, "ms"},
                                           {"/Disp", kSix, H5T_IEEE_F64LE, "um"},
                                           {"/load", kSix, H5T_IEEE_F64LE, "kN"},
                                           {"/rig/t", kSix, H5T_IEEE_F64LE, "s"}});
  with_columns(file, kMeasured, {}, [](const std::vector<Hdf5Column>& c) {
    CHECK(c[0].path == "/time");
    CHECK(c[1].path == "/Disp");  // names compare case-insensitively
    CHECK(c[2].path == "/load");
    CHECK(c[0].scale == exactly(1e-3));  // ms -> s
    CHECK(c[1].scale == exactly(1e-3));  // um -> mm
    CHECK(c[2].scale == exactly(1e3));   // kN -> N
    for (const auto& column : c) {
      CHECK(column.dataset);
      CHECK(column.axis == 0);
      CHECK(column.length == kSix.size());
      CHECK(points(column) == 6);
    }
  });
  // Only the roles asked for, in their order.
  with_columns(file, {Role::force, Role::time}, {}, [](const std::vector<Hdf5Column>& c) {
    CHECK(c[0].path == "/load");
    CHECK(c[1].path == "/time");
  });
}

TEST_CASE("the default layout takes, of several datasets named as usual, the first whose unit suits the role") {
  // "time" is preferred to "t", but holds forces; "position" is preferred to "disp", but has no unit.
  const auto file = written("suits.h5", {{"/time", kSix, H5T_IEEE_F64LE, "N"},
                                         {"/t", kSix, H5T_IEEE_F64LE, "min"},
                                         {"/position", kSix, H5T_IEEE_F64LE, std::nullopt},
                                         {"/disp", kSix, H5T_IEEE_F64LE, "m"}});
  with_columns(file, kDrive, {}, [](const std::vector<Hdf5Column>& c) {
    CHECK(c[0].path == "/t");
    CHECK(c[0].scale == exactly(60.0));  // min -> s
    CHECK(c[1].path == "/disp");
    CHECK(c[1].scale == exactly(1e3));  // m -> mm
  });
  // Where none suits, the first named as usual, and its unit the fault.
  const auto none = written("none_suits.h5", {{"/t", kSix, H5T_IEEE_F64LE, "N"}, {"/displacement", kSix, H5T_IEEE_F64LE, "mm"}});
  CHECK(error_of(none, kDrive) ==
        none + ": error: /t (time) has unit 'N' (its 'units' attribute), a force (N); time needs a unit of time (s), e.g. \"s\"");
  // A group of a usual name is not a candidate; the message lists what the root holds.
  const auto group = written("group.h5", {{"/time/values", kSix, H5T_IEEE_F64LE, "s"}, {"/displacement", kSix, H5T_IEEE_F64LE, "mm"}});
  CHECK(error_of(group, kDrive) ==
        group +
            ": error: no time dataset: the root group has none named as usual (time, t, test time, elapsed time); name the one that holds "
            "it: columns = \"time = /group/dataset\" (the root group holds displacement, time)");
}

TEST_CASE("named paths through groups, and a unit on the line overriding or standing in for the 'units' attribute") {
  const auto file = written("named.h5", {{"/rig/t", kSix, H5T_IEEE_F64LE, "s"},
                                         {"/rig/sensors/u", kSix, H5T_IEEE_F64LE, std::nullopt},
                                         {"/rig/sensors/f", kSix, H5T_IEEE_F64LE, "N"},
                                         {"/time", kSix, H5T_IEEE_F64LE, "s"}});
  with_columns(file, kMeasured, named({{Role::time, "/rig/t"}, {Role::displacement, "rig/sensors/u [um]"}, {Role::force, "/rig/sensors/f\t[kN]"}}),
               [](const std::vector<Hdf5Column>& c) {
                 CHECK(c[0].path == "/rig/t");  // named, though the root holds a "time"
                 CHECK(c[0].scale == exactly(1.0));
                 CHECK(c[1].path == "/rig/sensors/u");  // made absolute, the unit taken off
                 CHECK(c[1].scale == exactly(1e-3));    // the line's unit where the attribute is missing
                 CHECK(c[2].path == "/rig/sensors/f");
                 CHECK(c[2].scale == exactly(1e3));  // the line's unit over the attribute's
               });
  // The roles not named come from the default layout.
  with_columns(file, kDrive, named({{Role::displacement, "/rig/sensors/u [mm]"}}), [](const std::vector<Hdf5Column>& c) {
    CHECK(c[0].path == "/time");
    CHECK(c[1].path == "/rig/sensors/u");
  });
  // The line's unit is checked like the attribute's.
  CHECK(error_of(file, kDrive, named({{Role::time, "/rig/t [mm]"}, {Role::displacement, "/rig/sensors/u [mm]"}})) ==
        file + ": error: /rig/t (time) has unit 'mm' (on the line), a length (mm); time needs a unit of time (s), e.g. \"s\"");
}

TEST_CASE("with every role named, the root's other datasets are not read: an integer 'units' there is no fault") {
  const auto file = written("named_only.h5", {{"/rig/t", kSix, H5T_IEEE_F64LE, "s"}, {"/rig/u", kSix, H5T_IEEE_F64LE, "mm"}});
  add_dataset(file, "/notes", H5T_NATIVE_INT, {3});
  {
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t dataset = H5Dopen2(f, "/notes", H5P_DEFAULT);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t attribute = H5Acreate2(dataset, "units", H5T_NATIVE_INT, space, H5P_DEFAULT, H5P_DEFAULT);
    const int value = 7;
    REQUIRE(H5Awrite(attribute, H5T_NATIVE_INT, &value) >= 0);
    H5Aclose(attribute), H5Sclose(space), H5Dclose(dataset);
    REQUIRE(H5Fclose(f) >= 0);
  }
  with_columns(file, kDrive, named({{Role::time, "/rig/t"}, {Role::displacement, "/rig/u"}}), [](const std::vector<Hdf5Column>& c) {
    CHECK(c[0].path == "/rig/t");
    CHECK(c[1].path == "/rig/u");
  });
  // Where a role falls to the default layout, the root is read and its fault named.
  CHECK(error_of(file, kDrive, named({{Role::displacement, "/rig/u"}})).find("is not a string") != std::string::npos);
}

TEST_CASE("a vector's axis and length: rank 1, N x 1 and 1 x N") {
  const auto file = written("shapes.h5", {{"/line", {1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0}, H5T_IEEE_F64LE, "s"},
                                          {"/column", {1.0, 2.0, 3.0, 4.0, 5.0}, H5T_IEEE_F64LE, "mm", false, true}});
  add_dataset(file, "/row", H5T_IEEE_F64LE, {1, 9}, "N");
  add_dataset(file, "/one", H5T_IEEE_F64LE, {1, 1}, "N");
  with_columns(file, kMeasured, named({{Role::time, "/line"}, {Role::displacement, "/column"}, {Role::force, "/row"}}),
               [](const std::vector<Hdf5Column>& c) {
                 CHECK(c[0].axis == 0);
                 CHECK(c[0].length == 7);
                 CHECK(H5Sget_simple_extent_ndims(c[0].space.get()) == 1);
                 CHECK(c[1].axis == 0);
                 CHECK(c[1].length == 5);
                 CHECK(H5Sget_simple_extent_ndims(c[1].space.get()) == 2);
                 CHECK(c[2].axis == 1);
                 CHECK(c[2].length == 9);
                 CHECK(points(c[2]) == 9);
               });
  with_columns(file, {Role::force}, named({{Role::force, "/one"}}), [](const std::vector<Hdf5Column>& c) {
    CHECK(c[0].axis == 0);  // 1 x 1: read as N x 1
    CHECK(c[0].length == 1);
  });
}

TEST_CASE("any floating-point or integer type, its unit's scale the same") {
  const auto file = written(
      "types.h5", {{"/time", kSix, H5T_IEEE_F32LE, "ms"}, {"/displacement", kSix, H5T_STD_I32LE, "um"}, {"/force", kSix, H5T_STD_U16BE, "kN"}});
  with_columns(file, kMeasured, {}, [](const std::vector<Hdf5Column>& c) {
    const H5T_class_t expected[] = {H5T_FLOAT, H5T_INTEGER, H5T_INTEGER};
    for (std::size_t i = 0; i < c.size(); ++i) {
      const hid_t type = H5Dget_type(c[i].dataset.get());
      CHECK(H5Tget_class(type) == expected[i]);
      H5Tclose(type);
      CHECK(c[i].length == kSix.size());
    }
    CHECK(c[0].scale == exactly(1e-3));
    CHECK(c[1].scale == exactly(1e-3));
    CHECK(c[2].scale == exactly(1e3));
  });
}

TEST_CASE("layout faults are DataErrors naming the file and the dataset, with what to do") {
  const auto file = written("faults.h5", {{"/rig/t", kSix, H5T_IEEE_F64LE, "s"},
                                          {"/rig/u", kSix, H5T_IEEE_F64LE, "mm"},
                                          {"/bare", kSix, H5T_IEEE_F64LE, std::nullopt},
                                          {"/odd", kSix, H5T_IEEE_F64LE, "furlong"}});
  add_dataset(file, "/matrix", H5T_IEEE_F64LE, {3, 2}, "mm");
  add_dataset(file, "/cube", H5T_IEEE_F64LE, {2, 2, 2}, "mm");
  const hid_t text = H5Tcopy(H5T_C_S1);
  REQUIRE(H5Tset_size(text, 8) >= 0);
  add_dataset(file, "/labels", text, {6}, "mm");
  H5Tclose(text);
  auto displacement_at = [&](const std::string& path) { return error_of(file, {Role::displacement}, named({{Role::displacement, path}})); };

  SUBCASE("a dataset missing from its group") {
    CHECK(displacement_at("/rig/x") == file + ": error: no dataset /rig/x for displacement: there is no /rig/x; /rig holds t, u");
  }
  SUBCASE("a group missing on the path") {
    CHECK(displacement_at("/bench/rig/u") ==
          file + ": error: no dataset /bench/rig/u for displacement: there is no /bench; the root group holds bare, cube, labels, matrix, odd, rig");
    CHECK(displacement_at("/rig/u/x") == file + ": error: no dataset /rig/u/x for displacement: /rig/u is not a group");
  }
  SUBCASE("a group named instead of a dataset") {
    CHECK(displacement_at("/rig") == file + ": error: /rig (displacement) is a group, not a dataset; name a dataset in it: it holds t, u");
  }
  SUBCASE("no dataset named as usual in the root") {
    CHECK(error_of(file, {Role::force}) ==
          file +
              ": error: no force dataset: the root group has none named as usual (force, load, standard force, reaction force, f); name the one "
              "that holds it: columns = \"force = /group/dataset\" (the root group holds bare, cube, "
              "labels, matrix, odd, rig)");
  }
  SUBCASE("a matrix, not a vector") {
    CHECK(displacement_at("/matrix") ==
          file + ": error: /matrix (displacement) has rank 2 (3 x 2); rheo reads a vector: rank 1, or an N x 1 or 1 x N matrix");
    CHECK(displacement_at("/cube") == file + ": error: /cube (displacement) has rank 3; rheo reads a vector: rank 1, or an N x 1 or 1 x N matrix");
  }
  SUBCASE("strings, not numbers") {
    CHECK(displacement_at("/labels") ==
          file + ": error: /labels (displacement) holds strings, not numbers; rheo reads a dataset of floating-point or integer numbers");
  }
  SUBCASE("a unit of the wrong kind, or unknown") {
    CHECK(displacement_at("/rig/t") ==
          file +
              ": error: /rig/t (displacement) has unit 's' (its 'units' attribute), a time (s); displacement needs a unit of length (mm), "
              "e.g. \"mm\"");
    CHECK(displacement_at("/odd") ==
          file +
              ": error: /odd (displacement) has unit 'furlong' (its 'units' attribute), which rheo does not know; use units such as s, ms, "
              "mm, um, m, N, kN");
  }
  SUBCASE("no unit anywhere") {
    CHECK(displacement_at("/bare") == file +
                                          ": error: /bare (displacement) has no unit: no 'units' attribute; give it one (a string, e.g. "
                                          "\"mm\"), or write the unit after the dataset: columns = \"displacement = /bare [mm]\"");
    CHECK(displacement_at("/bare []").find(file + ": error: /bare (displacement) has no unit") == 0);
  }
}

}  // namespace hdf5_layout_test
