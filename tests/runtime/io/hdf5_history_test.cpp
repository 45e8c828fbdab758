// The HDF5 history reader against files written here with the HDF5 C API (hdf5_support.hpp) in
// the layouts other tools write (float32, integers, chunked and contiguous, N x 1 matrices,
// fixed- and variable-length unit strings, units on the line instead of attributes): the values
// written, converted by their units, whatever the piece size; and each fault a DataError naming
// the file, the dataset and, for values, the index.
#include "runtime/io/hdf5_history.hpp"

#include "hdf5_support.hpp"
#include "runtime/core/errors.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <unistd.h>
#include <vector>

namespace hdf5_history_test {

using namespace rheo::runtime;
namespace fs = std::filesystem;
using rheo::test::hdf5::DatasetSpec;
using rheo::test::hdf5::write_file;

namespace {

fs::path scratch() {
  const auto dir = fs::temp_directory_path() / fmt::format("rheo-hdf5-history-{}", ::getpid());
  fs::create_directories(dir);
  return dir;
}

std::vector<double> ramp(std::size_t n, double step, double offset = 0.0) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = offset + static_cast<double>(i) * step;
  return v;
}
std::vector<double> wave(std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = 2.0 * std::sin(0.01 * static_cast<double>(i)) + 0.125;
  return v;
}

ColumnReading named(std::vector<std::pair<Role, std::string>> columns) { return ColumnReading{std::move(columns), {}, {}}; }

struct Read {
  std::vector<double> time, displacement, force;
  std::size_t pieces = 0;
};

Read read_all(const std::string& file, const ColumnReading& reading, bool force, std::size_t piece, bool from_rest = false) {
  Hdf5HistoryReader reader(file, nullptr, reading, force, from_rest, piece);
  Read r;
  DrivePiece p;
  std::vector<double> f;
  while (reader.next(p, force ? &f : nullptr)) {
    ++r.pieces;
    r.time.insert(r.time.end(), p.time.begin(), p.time.end());
    r.displacement.insert(r.displacement.end(), p.displacement.begin(), p.displacement.end());
    r.force.insert(r.force.end(), f.begin(), f.end());
  }
  return r;
}

std::string error_of(const std::string& file, const ColumnReading& reading = {}, bool force = false, bool from_rest = false) {
  try {
    read_all(file, reading, force, 5, from_rest);
  } catch (const DataError& e) {
    return e.what();
  }
  return "";
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

}  // namespace

TEST_CASE("an HDF5 history in the default layout reads as written, bit for bit, whatever the piece size") {
  const auto file = (scratch() / "default.h5").string();
  const auto t = ramp(103, 1e-3, 5.0), u = wave(103), f = ramp(103, 0.5, -3.0);
  write_file(file, {{"/time", t, H5T_IEEE_F64LE, "s"}, {"/displacement", u, H5T_IEEE_F64LE, "mm", true}, {"/force", f, H5T_IEEE_F64LE, "N"}});
  for (const std::size_t piece : {1UL, 7UL, 64UL, 1000UL}) {
    const Read r = read_all(file, {}, true, piece);
    std::vector<double> shifted(t.size());
    for (std::size_t i = 0; i < t.size(); ++i) shifted[i] = t[i] - t[0];  // the drive starts at 0, as from a CSV table
    CHECK(same_bits(r.time, shifted));
    CHECK(same_bits(r.displacement, u));
    CHECK(same_bits(r.force, f));
    CHECK(r.pieces == (103 + piece - 1) / piece);
  }
}

TEST_CASE("an HDF5 history at named paths, float32, integers, N x 1, chunked or contiguous, units converted") {
  const auto file = (scratch() / "rig.h5").string();
  const std::vector<double> t_ms = ramp(50, 2.0), u_um = wave(50), f_kn = ramp(50, 0.25, 1.0);
  write_file(file, {{.path = "/rig/run 1/t", .values = t_ms, .type = H5T_STD_I32LE, .units = "ms", .chunked = true},
                    {.path = "/rig/run 1/u", .values = u_um, .type = H5T_IEEE_F32LE, .units = "um", .column = true, .fixed_string = true},
                    {.path = "/rig/run 1/F", .values = f_kn, .type = H5T_IEEE_F32BE, .units = "kN", .chunked = true, .column = true}});
  const Read r = read_all(file, named({{Role::time, "/rig/run 1/t"}, {Role::displacement, "rig/run 1/u"}, {Role::force, "/rig/run 1/F"}}), true, 9);
  REQUIRE(r.time.size() == 50);
  for (std::size_t i = 0; i < 50; ++i) {
    CHECK(r.time[i] == t_ms[i] * 0.001);                                                   // integers are exact; ms to s
    CHECK(r.displacement[i] == static_cast<double>(static_cast<float>(u_um[i])) * 0.001);  // float32 as stored; um to mm
    CHECK(r.force[i] == static_cast<double>(static_cast<float>(f_kn[i])) * 1000.0);
  }
}

TEST_CASE("units on the line stand in for missing attributes: without either, an error with advice") {
  const auto file = (scratch() / "bare.h5").string();
  write_file(file, {{.path = "/t", .values = ramp(10, 0.1)}, {.path = "/u", .values = wave(10)}});
  const Read r = read_all(file, named({{Role::time, "/t [s]"}, {Role::displacement, "/u [cm]"}}), false, 4);
  REQUIRE(r.displacement.size() == 10);
  CHECK(r.displacement[3] == wave(10)[3] * 10.0);
  CHECK(error_of(file) == fmt::format("{}: error: /t (time) has no unit: no 'units' attribute; give it one (a string, e.g. \"s\"), or write the "
                                      "unit after the dataset: columns = \"time = /t [s]\"",
                                      file));
}

TEST_CASE("HDF5 history faults name the file, the dataset and the index, with advice") {
  const auto dir = scratch();
  const auto t = ramp(20, 0.1), u = wave(20);
  auto faulty = [&](const std::string& name, std::vector<DatasetSpec> specs) {
    const auto file = (dir / name).string();
    write_file(file, specs);
    return file;
  };
  SUBCASE("not HDF5") {
    const auto file = (dir / "text.h5").string();
    std::ofstream(file) << "time [s],displacement [mm]\n0,0\n1,1\n";
    CHECK(error_of(file).find(file + ": error: this is not an HDF5 file") == 0);
  }
  SUBCASE("missing file") { CHECK(error_of((dir / "none.h5").string()).find("No such file") != std::string::npos); }
  SUBCASE("missing dataset and group") {
    const auto file = faulty("missing.h5", {{"/rig/t", t, H5T_IEEE_F64LE, "s"}, {"/rig/u", u, H5T_IEEE_F64LE, "mm"}});
    CHECK(error_of(file, named({{Role::time, "/rig/t"}, {Role::displacement, "/rig/x"}})) ==
          file + ": error: no dataset /rig/x for displacement: there is no /rig/x; /rig holds t, u");
    CHECK(error_of(file, named({{Role::time, "/bench/t"}, {Role::displacement, "/rig/u"}})) ==
          file + ": error: no dataset /bench/t for time: there is no /bench; the root group holds rig");
    CHECK(error_of(file, named({{Role::time, "/rig"}, {Role::displacement, "/rig/u"}})) ==
          file + ": error: /rig (time) is a group, not a dataset; name a dataset in it: it holds t, u");
    CHECK(error_of(file).find(file + ": error: no time dataset: the root group has none named as usual (time, t, test time, elapsed time)") == 0);
  }
  SUBCASE("rank and type") {
    const auto file = faulty("rank.h5", {{"/time", t, H5T_IEEE_F64LE, "s"}, {"/displacement", u, H5T_IEEE_F64LE, "mm"}});
    {  // a 4 x 5 matrix, and strings, added with the C API
      const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
      const hsize_t dims[2] = {4, 5};
      const hid_t space = H5Screate_simple(2, dims, nullptr);
      const hid_t d = H5Dcreate2(f, "/matrix", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, ramp(20, 1.0).data());
      H5Dclose(d), H5Sclose(space);
      const hid_t text = H5Tcopy(H5T_C_S1);
      H5Tset_size(text, 8);
      const hsize_t n = 20;
      const hid_t line = H5Screate_simple(1, &n, nullptr);
      const hid_t s = H5Dcreate2(f, "/names", text, line, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      H5Dclose(s), H5Sclose(line), H5Tclose(text), H5Fclose(f);
    }
    CHECK(error_of(file, named({{Role::displacement, "/matrix"}})) ==
          file + ": error: /matrix (displacement) has rank 2 (4 x 5); rheo reads a vector: rank 1, or an N x 1 or 1 x N matrix");
    CHECK(error_of(file, named({{Role::displacement, "/names"}})) ==
          file + ": error: /names (displacement) holds strings, not numbers; rheo reads a dataset of floating-point or integer numbers");
  }
  SUBCASE("units unknown or of another kind") {
    const auto file = faulty("units.h5", {{"/time", t, H5T_IEEE_F64LE, "furlong"}, {"/displacement", u, H5T_IEEE_F64LE, "mm"}});
    CHECK(error_of(file).find("/time (time) has unit 'furlong' (its 'units' attribute), which rheo does not know") != std::string::npos);
    CHECK(error_of(file, named({{Role::time, "/displacement [mm]"}, {Role::displacement, "/displacement"}})) ==
          file + ": error: /displacement (time) has unit 'mm' (on the line), a length (mm); time needs a unit of time (s), e.g. \"s\"");
  }
  SUBCASE("lengths") {
    const auto file = faulty("lengths.h5", {{"/time", t, H5T_IEEE_F64LE, "s"}, {"/displacement", wave(19), H5T_IEEE_F64LE, "mm"}});
    CHECK(error_of(file) == file +
                                ": error: the datasets differ in length: /time has 20 samples, /displacement has 19; a history needs a "
                                "displacement at every time");
    const auto one = faulty("one.h5", {{"/time", {0.0}, H5T_IEEE_F64LE, "s"}, {"/displacement", {0.0}, H5T_IEEE_F64LE, "mm"}});
    CHECK(error_of(one) == one + ": error: /time has 1 sample; a history needs at least two");
  }
  SUBCASE("values") {
    auto with = [&](const char* name, std::vector<double> time, std::vector<double> disp, std::vector<double> force = {}) {
      std::vector<DatasetSpec> specs{{"/time", time, H5T_IEEE_F64LE, "s"}, {"/displacement", disp, H5T_IEEE_F64LE, "mm"}};
      if (!force.empty()) specs.push_back({"/force", force, H5T_IEEE_F64LE, "N"});
      return faulty(name, specs);
    };
    auto nan_at = [](std::vector<double> v, std::size_t i) {
      v[i] = std::numeric_limits<double>::quiet_NaN();
      return v;
    };
    const auto tn = with("nan_t.h5", nan_at(t, 13), u);
    CHECK(error_of(tn) == tn + ": error: /time[13] (time) is nan; every time must be a finite number: remove the sample or mend the recording");
    const auto un = with("nan_u.h5", t, nan_at(u, 6));
    CHECK(error_of(un).find(": error: /displacement[6] (displacement) is nan;") != std::string::npos);
    const auto fn = with("nan_f.h5", t, u, nan_at(ramp(20, 1.0), 19));
    CHECK(error_of(fn, {}, true).find(": error: /force[19] (force) is nan;") != std::string::npos);
    CHECK(error_of(fn, {}, false).empty());  // a drive does not read the force
    auto back = t;
    back[11] = back[10];
    const auto tb = with("repeat.h5", back, u);
    CHECK(error_of(tb) == tb + ": error: /time[11] (time) = 1 s is not after [10] = 1 s; time must increase from sample to sample: remove "
                               "repeated samples or sort the history by time");
    auto far = u;
    far[8] = 1e25;
    const auto uf = with("far.h5", t, far);
    CHECK(error_of(uf) == uf + ": error: /displacement[8] (displacement) = 1e+25 mm is beyond the 1e+20 mm a rig can drive; check the "
                               "dataset's unit");
    const auto zero = with("zero.h5", t, u, std::vector<double>(20, 0.0));
    CHECK(error_of(zero, {}, true) == zero + ": error: every force in /force is zero; a fit needs a force signal: check the dataset and its unit");
    const auto rest = with("rest.h5", t, u);
    CHECK(error_of(rest, {}, false, true).find(": error: /displacement[0] (displacement) is 0.125 mm; start = rest needs displacement 0") !=
          std::string::npos);
  }
}

TEST_CASE("read_hdf5_drive and read_hdf5_history hold what the reader hands out") {
  const auto file = (scratch() / "whole.h5").string();
  const auto t = ramp(70000, 1e-4), u = wave(70000), f = ramp(70000, 0.01, 1.0);  // more than one piece
  write_file(file, {{"/time", t, H5T_IEEE_F64LE, "s"}, {"/displacement", u, H5T_IEEE_F64LE, "mm"}, {"/force", f, H5T_IEEE_F64LE, "N"}});
  const Drive drive = read_hdf5_drive(file, nullptr, {}, false);
  CHECK(same_bits(drive.time, t));
  CHECK(same_bits(drive.displacement, u));
  const HistoryData h = read_hdf5_history(file, nullptr, {});
  CHECK(same_bits(h.drive.time, t));
  CHECK(same_bits(h.force, f));
  CHECK(h.force_scale == f.back());
  CHECK(h.rows.size() == 70000);
}

TEST_CASE("histories held whole are bounded before they are read: a drive by its samples, a measured history by its bytes") {
  const auto file = (scratch() / "huge.h5").string();
  {  // chunked datasets of 3e7 samples never written: HDF5 stores no chunk of them
    const hid_t f = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const hsize_t n = 30'000'001, chunk = 65536;
    for (const char* name : {"/time", "/displacement", "/force"}) {
      const hid_t space = H5Screate_simple(1, &n, nullptr);
      const hid_t layout = H5Pcreate(H5P_DATASET_CREATE);
      H5Pset_chunk(layout, 1, &chunk);
      const hid_t d = H5Dcreate2(f, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, layout, H5P_DEFAULT);
      rheo::test::hdf5::write_units(d, name[1] == 't' ? "s" : name[1] == 'd' ? "mm" : "N", false);
      H5Dclose(d), H5Pclose(layout), H5Sclose(space);
    }
    H5Fclose(f);
  }
  CHECK_THROWS_WITH_AS(read_hdf5_drive(file, nullptr, {}, false),
                       (file + ": error: the history has 30000001 samples, more than the 10000000 rheo holds whole (SUNDIALS, JSON output); write it "
                               "as CSV or HDF5 on the fixed-step solver, which streams it, or split the file")
                           .c_str(),
                       DataError);
  CHECK_THROWS_WITH_AS(read_hdf5_history(file, nullptr, {}),
                       (file + ": error: the history has 30000001 samples, more than the 22369621 a fit or report holds (512 MiB at 24 bytes a "
                               "sample); fit a part of it, or resample it")
                           .c_str(),
                       DataError);
}

}  // namespace hdf5_history_test
