// MATLAB .mat files against files written here with the HDF5 C API as MATLAB v7.3 writes them
// (matlab_support.hpp: the 512-byte user block with MATLAB's header, MATLAB_class attributes,
// reversed dimensions, structs as groups): the variables read as written, converted by their
// units, by the default layout's names and by paths (/rig/t or rig.t); every variable that does
// not hold real numbers, and every MAT-file that is not v7.3, refused with its message.
#include "runtime/io/matlab_file.hpp"

#include "matlab_support.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/io/fit_data.hpp"
#include "runtime/io/hdf5_history.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace matlab_file_test {

using namespace rheo::runtime;
namespace fs = std::filesystem;
using rheo::test::matlab::Kind;
using rheo::test::matlab::Variable;
using rheo::test::matlab::write_mat;

namespace {

fs::path scratch() {
  const auto dir = fs::temp_directory_path() / fmt::format("rheo-matlab-{}", ::getpid());
  fs::create_directories(dir);
  return dir;
}

std::vector<double> ramp(std::size_t n, double step) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<double>(i) * step;
  return v;
}
std::vector<double> wave(std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = 2.0 * std::sin(0.1 * static_cast<double>(i)) + 0.25;
  return v;
}

ColumnReading named(std::vector<std::pair<Role, std::string>> columns) { return ColumnReading{std::move(columns), {}, {}}; }

HistoryData read(const std::string& file, const ColumnReading& reading) { return read_hdf5_history(file, nullptr, reading); }

std::string error_of(const std::string& file, const ColumnReading& reading = {}) {
  try {
    read(file, reading);
  } catch (const DataError& e) {
    return e.what();
  }
  return "";
}

std::string error_of_variable(const std::string& name, Variable bad, const std::string& role = "displacement") {
  const auto file = (scratch() / name).string();
  bad.path = role == "time" ? "/t" : role == "force" ? "/F" : "/d";
  std::vector<Variable> variables{{.path = "/t", .values = ramp(8, 0.5)}, {.path = "/d", .values = wave(8)}, {.path = "/F", .values = wave(8)}};
  variables[role == "time" ? 0 : role == "force" ? 2 : 1] = bad;
  write_mat(file, variables);
  return error_of(file, named({{Role::time, "t [s]"}, {Role::displacement, "d [mm]"}, {Role::force, "F [N]"}}));
}

}  // namespace

TEST_CASE("names, headers and struct fields of MATLAB files") {
  CHECK(is_matlab_name("run.mat"));
  CHECK(is_matlab_name("dir/RUN.MAT"));
  CHECK_FALSE(is_matlab_name("run.mat.csv"));
  CHECK_FALSE(is_matlab_name("format"));
  CHECK(reads_as_hdf5("run.Mat"));
  CHECK(reads_as_hdf5("run.h5"));
  CHECK_FALSE(reads_as_hdf5("run.csv"));
  CHECK_FALSE(is_hdf5_name("run.mat"));  // an output named .mat is not written as HDF5
  CHECK(matlab_header("MATLAB 5.0 MAT-file, Platform: PCWIN64") == MatHeader::v5);
  CHECK(matlab_header("MATLAB 7.3 MAT-file, Platform: GLNXA64") == MatHeader::v73);
  CHECK(matlab_header("MATLAB 5.0 MAT") == MatHeader::none);
  CHECK(matlab_header("\x89HDF\r\n") == MatHeader::none);
  CHECK(matlab_field_path("run.mat", "rig.t") == "rig/t");
  CHECK(matlab_field_path("run.mat", "a.b.c") == "a/b/c");
  CHECK(matlab_field_path("run.mat", "/rig/t.1") == "/rig/t.1");  // a path with '/' is HDF5's, as written
  CHECK(matlab_field_path("run.h5", "rig.t") == "rig.t");         // HDF5 names may hold '.'
}

TEST_CASE("a v7.3 MAT-file reads as written: row and column vectors, single and integer classes, units on the line") {
  const auto file = (scratch() / "run.mat").string();
  const std::vector<double> t_ms = ramp(40, 2.0), u_um = wave(40), f_kn = ramp(40, 0.125);
  write_mat(file, {{.path = "/t", .values = t_ms, .matlab_class = "int32", .type = H5T_STD_I32LE, .row = false},
                   {.path = "/x", .values = u_um, .matlab_class = "single", .type = H5T_IEEE_F32LE},
                   {.path = "/F", .values = f_kn}});
  const HistoryData h = read(file, named({{Role::time, "t [ms]"}, {Role::displacement, "x [um]"}, {Role::force, "F [kN]"}}));
  REQUIRE(h.drive.time.size() == 40);
  for (std::size_t i = 0; i < 40; ++i) {
    CHECK(h.drive.time[i] == t_ms[i] * 0.001);
    CHECK(h.drive.displacement[i] == static_cast<double>(static_cast<float>(u_um[i])) * 0.001);  // single as stored
    CHECK(h.force[i] == f_kn[i] * 1000.0);
  }
  CHECK(h.force_scale == f_kn.back() * 1000.0);
  // The same variables, MATLAB's usual names found without naming them, given 'units' attributes.
  const auto with_units = (scratch() / "units.mat").string();
  write_mat(with_units, {{.path = "/time", .values = t_ms, .units = "ms"},
                         {.path = "/disp", .values = u_um, .row = false, .units = "um"},
                         {.path = "/force", .values = f_kn, .units = "kN"}});
  const HistoryData d = read(with_units, {});
  REQUIRE(d.drive.displacement.size() == 40);
  CHECK(d.drive.time == h.drive.time);
  CHECK(d.drive.displacement[7] == u_um[7] * 0.001);
  CHECK(d.force == h.force);
}

TEST_CASE("a struct's fields by path or as MATLAB writes them, a struct itself named is refused with its fields") {
  const auto file = (scratch() / "rig.mat").string();
  const std::vector<double> t = ramp(12, 0.25), u = wave(12), f = ramp(12, 3.0);
  write_mat(file, {{.path = "/rig/t", .values = t}, {.path = "/rig/u", .values = u, .row = false}, {.path = "/rig/F", .values = f}});
  const HistoryData a = read(file, named({{Role::time, "/rig/t [s]"}, {Role::displacement, "rig/u [mm]"}, {Role::force, "rig.F [N]"}}));
  CHECK(a.drive.time == t);
  CHECK(a.drive.displacement == u);
  CHECK(a.force == f);
  CHECK(error_of(file, named({{Role::time, "rig [s]"}, {Role::displacement, "rig.u [mm]"}, {Role::force, "rig.F [N]"}})) ==
        fmt::format("{}: error: /rig (time) is a MATLAB struct, not an array; name one of its fields, e.g. columns = \"time = rig.field\": it "
                    "holds F, t, u",
                    file));
  CHECK(error_of(file, named({{Role::time, "rig.s [s]"}})) ==
        fmt::format("{}: error: no dataset /rig/s for time: there is no /rig/s; /rig holds F, t, u", file));
}

TEST_CASE("MATLAB variables carry no unit: the default layout finds them and says how to name them with theirs") {
  const auto file = (scratch() / "bare.mat").string();
  write_mat(file, {{.path = "/t", .values = ramp(6, 0.5)}, {.path = "/x", .values = wave(6)}, {.path = "/F", .values = wave(6)}});
  CHECK(error_of(file) == fmt::format("{}: error: /t (time) has no unit: MATLAB saves none, and it has no 'units' attribute; write each "
                                      "variable's unit after it: columns = \"time = t [s], displacement = x [mm], force = F [N]\"",
                                      file));
  // Units on the line for some roles: those kept in the advice.
  CHECK(error_of(file, named({{Role::time, "t [ms]"}})) ==
        fmt::format("{}: error: /x (displacement) has no unit: MATLAB saves none, and it has no 'units' attribute; write each variable's "
                    "unit after it: columns = \"time = t [ms], displacement = x [mm], force = F [N]\"",
                    file));
  // MATLAB's own #refs# group is not listed among the variables.
  const auto cells = (scratch() / "cells.mat").string();
  write_mat(cells, {{.path = "/c", .values = {1.0, 2.0}, .kind = Kind::cell}, {.path = "/t", .values = ramp(6, 0.5)}});
  CHECK(error_of(cells, named({{Role::time, "t [s]"}})) ==
        fmt::format("{}: error: no displacement dataset: the root group has none named as usual (displacement, position, stroke, travel, "
                    "deflection, disp, x, u); name the one that holds it: columns = \"displacement = /group/dataset\" (the root group holds c, t)",
                    cells));
}

TEST_CASE("variables that are not real numbers are refused naming the variable, with what to do") {
  auto expect = [](const std::string& name, const Variable& bad, const std::string& role, const std::string& message) {
    const auto file = (scratch() / name).string();
    CAPTURE(name);
    CHECK(error_of_variable(name, bad, role) == file + ": error: " + message);
  };
  expect("char.mat", {.values = {116.0, 105.0}, .kind = Kind::text}, "time",
         "/t (time) is a MATLAB char array (text), not numbers; save the time as a numeric array (double) in MATLAB, e.g. t = str2double(t)");
  expect("logical.mat", {.values = {1.0, 0.0, 1.0}, .kind = Kind::logical}, "displacement",
         "/d (displacement) is a MATLAB logical array (true/false), not measurements; save the displacement as a numeric array (double) in "
         "MATLAB");
  expect("cell.mat", {.values = {1.0, 2.0}, .kind = Kind::cell}, "force",
         "/F (force) is a MATLAB cell array; save the force as a numeric array (double) in MATLAB, e.g. F = cell2mat(F)");
  expect("empty.mat", {.kind = Kind::empty}, "force",
         "/F (force) is an empty MATLAB array (double); a history needs its samples: save the variable that holds them");
  expect("complex.mat", {.values = wave(8), .kind = Kind::complex}, "displacement",
         "/d (displacement) holds complex numbers; rheo reads real ones: save the real part, e.g. d = real(d)");
  expect("sparse.mat", {.values = wave(8), .kind = Kind::sparse}, "displacement",
         "/d (displacement) is a MATLAB sparse matrix; save it full, e.g. d = full(d)");
  expect("datetime.mat", {.values = wave(8), .matlab_class = "datetime", .type = H5T_STD_U32LE}, "time",
         "/t (time) is a MATLAB datetime object, not a numeric array; save the time as a numeric array (double) in MATLAB");
  // Integers of any width are numbers: read, converted.
  CHECK(error_of_variable("uint16.mat", {.values = {1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0}, .matlab_class = "uint16", .type = H5T_STD_U16LE}, "force")
            .empty());
}

TEST_CASE("a MAT-file that is not v7.3 is refused naming the file, with what to do") {
  const auto v5 = (scratch() / "old.mat").string();
  rheo::test::matlab::write_v5_mat(v5);
  CHECK(error_of(v5) == fmt::format("{}: error: this is a MATLAB v5/v7 MAT-file (the default of save), which rheo cannot read; re-save it as "
                                    "v7.3 (an HDF5 file) in MATLAB, e.g. save('old.mat', 't', 'x', 'F', '-v7.3'), or export the history as "
                                    "a CSV table",
                                    v5));
  const auto text = (scratch() / "text.mat").string();
  std::ofstream(text) << "time [s],displacement [mm]\n0,0\n1,1\n";
  CHECK(error_of(text) == fmt::format("{}: error: this is not a MATLAB v7.3 MAT-file (rheo reads a file named .mat as one, an HDF5 file); "
                                      "re-save it in MATLAB with save(..., '-v7.3'), or export the history as a CSV table",
                                      text));
  // A drive read whole and a streamed one say the same.
  CHECK_THROWS_WITH_AS(read_hdf5_drive(v5, nullptr, {}, false), doctest::Contains("MATLAB v5/v7 MAT-file"), DataError);
}

TEST_CASE("a MATLAB file is measured data: a history, its data line's settings of other kinds refused") {
  const auto file = (scratch() / "measured.mat").string();
  write_mat(file, {{.path = "/t", .values = ramp(10, 0.1)}, {.path = "/x", .values = wave(10)}, {.path = "/F", .values = wave(10)}});
  DataReading reading;
  reading.columns = named({{Role::time, "t [s]"}, {Role::displacement, "x [mm]"}, {Role::force, "F [N]"}});
  const FitDataSet set = read_fit_data(file, 1.0, nullptr, reading);
  REQUIRE_FALSE(set.is_harmonic());
  CHECK(set.history().force == wave(10));
  reading.step = "Amplitude sweep";
  CHECK_THROWS_WITH_AS(
      read_fit_data(file, 1.0, nullptr, reading),
      (file + ": error: a MATLAB file is read as a history, so the data line's step (of a TRIOS export) does not apply; remove it").c_str(),
      DataError);
}

}  // namespace matlab_file_test
