// HDF5 histories through the command line (#28): `rheo simulate` writes a history as HDF5 with
// the values of its CSV result bit for bit, reads one back (streamed, and whole on SUNDIALS) with
// the results of the CSV route bit for bit; `rheo fit` fits an HDF5 history as it fits the same
// history as CSV; a fault names the dataset and index, exits 4 and puts nothing in place. MATLAB
// v7.3 .mat files (HDF5 behind a user block) are read as histories and measured data the same way.
#include "cli_support.hpp"
#include "hdf5_support.hpp"
#include "matlab_support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace cli_hdf5_test {

namespace fs = std::filesystem;
namespace h5 = rheo::test::hdf5;
namespace mat = rheo::test::matlab;
using rheo::test::run_rheo;

namespace {

fs::path dir() { return rheo::test::scratch_directory("hdf5-cli"); }

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The columns of a CSV result rheo wrote (shortest round-trip numbers: read back exactly),
// by name without the unit: "time", "rubber.force".
std::vector<std::pair<std::string, std::vector<double>>> csv_columns(const fs::path& file) {
  std::istringstream in(read(file));
  std::string line;
  do std::getline(in, line);
  while (line.starts_with('#'));
  std::vector<std::pair<std::string, std::vector<double>>> columns;
  std::istringstream names(line);
  for (std::string name; std::getline(names, name, ',');) columns.emplace_back(name.substr(0, name.find(" [")), std::vector<double>{});
  while (std::getline(in, line)) {
    const char* p = line.data();
    const char* end = line.data() + line.size();
    for (auto& column : columns) {
      double v = 0.0;
      const auto [next, ec] = std::from_chars(p, end, v);
      REQUIRE(ec == std::errc{});
      column.second.push_back(v);
      p = next + (next < end ? 1 : 0);
    }
  }
  return columns;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

// The dataset of a CSV column's name: "time" -> /time, "outer.m1.force" -> /elements/outer.m1/force.
std::string dataset_of(const std::string& column) {
  if (column == "time" || column == "displacement" || column == "force") return "/" + column;
  const auto dot = column.rfind('.');
  return "/elements/" + column.substr(0, dot) + "/" + column.substr(dot + 1);
}

// The rows of a CSV result without its comment line (which names the input file).
std::string without_comments(const std::string& text) { return text.substr(text.find("\ntime") + 1); }

const std::string kModel =
    "model d {\n  yeoh rubber (D10 = 389.4253 N/mm, D20 = -2.1094 N/mm^3, D30 = 0.0786 N/mm^5)\n  maxwell m1 (k = 61.476 N/mm, tau = 0.004335 s)\n"
    "  friction f1 (k = 1016.6 N/mm, uy = 101.58 um)\n}\n";

void write_drive(const fs::path& path, int rows) {
  std::ofstream out(path);
  out << "time [ms],displacement [um]\n";  // units converted on the way in
  for (int k = 0; k < rows; ++k) out << fmt::format("{},{}\n", k * 0.1, 1e3 * (2.0 * std::sin(k * 9.4e-4) + 0.1 * std::sin(k * 0.0145)));
}

void write_model(const fs::path& path, const std::string& file, const std::string& more = "") {
  std::ofstream(path) << kModel << fmt::format("simulate {{\n  history file = \"{}\"{}\n}}\n", file, more);
}

}  // namespace

TEST_CASE("simulate writes a history as HDF5 bit for bit as its CSV, and reads it back as the CSV route reads the CSV") {
  write_drive(dir() / "drive.csv", 70000);  // more than one chunk and piece
  write_model(dir() / "from_csv.rheo", "drive.csv", ", substeps = 2");
  const auto csv = run_rheo(fmt::format("simulate '{}' --elements -o '{}'", (dir() / "from_csv.rheo").string(), (dir() / "a.csv").string()));
  REQUIRE(csv.code == 0);
  const auto h5out = run_rheo(fmt::format("simulate '{}' --elements -o '{}'", (dir() / "from_csv.rheo").string(), (dir() / "a.h5").string()));
  CAPTURE(h5out.err);
  REQUIRE(h5out.code == 0);
  CHECK(h5out.err.find("139999 samples written to " + (dir() / "a.h5").string()) != std::string::npos);
  const auto columns = csv_columns(dir() / "a.csv");
  REQUIRE(columns.size() == 3 + 2 * 3);
  for (const auto& column : columns) {  // not a structured binding: Clang 14 cannot capture one
    const auto& name = std::get<0>(column);
    const auto& values = std::get<1>(column);
    CAPTURE(name);
    CHECK(same_bits(h5::read_dataset((dir() / "a.h5").string(), dataset_of(name)), values));
  }
  CHECK(h5::read_string_attribute((dir() / "a.h5").string(), "/force", "units") == "N");

  // The results read back as drives: HDF5 (streamed; whole on SUNDIALS) against CSV.
  write_model(dir() / "from_h5.rheo", "a.h5");
  write_model(dir() / "from_a_csv.rheo", "a.csv");
  for (const std::string solver : {"fixed", "sundials"}) {
    CAPTURE(solver);
    const auto via_h5 = run_rheo(
        fmt::format("simulate '{}' --solver {} -o '{}'", (dir() / "from_h5.rheo").string(), solver, (dir() / "b.csv").string()));
    CAPTURE(via_h5.err);
    REQUIRE(via_h5.code == 0);
    const auto via_csv = run_rheo(
        fmt::format("simulate '{}' --solver {} -o '{}'", (dir() / "from_a_csv.rheo").string(), solver, (dir() / "c.csv").string()));
    REQUIRE(via_csv.code == 0);
    CHECK(without_comments(read(dir() / "b.csv")) == without_comments(read(dir() / "c.csv")));
    // HDF5 in and out, held whole on SUNDIALS.
    const auto both = run_rheo(fmt::format("simulate '{}' --solver {} -o '{}'", (dir() / "from_h5.rheo").string(), solver, (dir() / "b.h5").string()));
    REQUIRE(both.code == 0);
    for (const auto& [name, values] : csv_columns(dir() / "c.csv"))
      CHECK(same_bits(h5::read_dataset((dir() / "b.h5").string(), dataset_of(name)), values));
  }
}

TEST_CASE("a history protocol reads HDF5 datasets at the paths its columns name, with units on the line") {
  const std::vector<double> t{0.0, 1.0, 2.0, 3.0, 4.0}, u{0.0, 100.0, 200.0, 100.0, 0.0};  // ms and um
  h5::write_file((dir() / "rig.h5").string(),
                 {{.path = "/rig/t", .values = t, .type = H5T_IEEE_F32LE}, {.path = "/rig/u", .values = u, .units = "um"}});
  std::ofstream(dir() / "rig.csv") << "time [ms],displacement [um]\n0,0\n1,100\n2,200\n3,100\n4,0\n";
  write_model(dir() / "rig.rheo", "rig.h5", ", columns = \"time = /rig/t [ms], displacement = rig/u\"");
  write_model(dir() / "rig_csv.rheo", "rig.csv");
  const auto a = run_rheo(fmt::format("simulate '{}'", (dir() / "rig.rheo").string()));
  CAPTURE(a.err);
  REQUIRE(a.code == 0);
  const auto b = run_rheo(fmt::format("simulate '{}'", (dir() / "rig_csv.rheo").string()));
  REQUIRE(b.code == 0);
  CHECK(without_comments(a.out) == without_comments(b.out));
  // A CSV history honours columns too.
  std::ofstream(dir() / "odd.csv") << "zeit [ms],weg [um]\n0,0\n1,100\n2,200\n3,100\n4,0\n";
  write_model(dir() / "odd.rheo", "odd.csv", ", columns = \"time = zeit, displacement = weg\"");
  const auto c = run_rheo(fmt::format("simulate '{}'", (dir() / "odd.rheo").string()));
  REQUIRE(c.code == 0);
  CHECK(without_comments(c.out) == without_comments(b.out));
  // Roles a history does not read are refused where they are written.
  write_model(dir() / "bad.rheo", "odd.csv", ", columns = \"force = F\"");
  const auto bad = run_rheo(fmt::format("check '{}'", (dir() / "bad.rheo").string()));
  CHECK(bad.code != 0);
  CHECK(bad.err.find("columns: 'force' is not a role rheo reads; use time, displacement") != std::string::npos);
}

TEST_CASE("a fault late in an HDF5 history: dataset and index, exit 4, nothing put in place, no temporary left") {
  const fs::path out = dir() / "late_out";
  fs::create_directories(out);
  std::ofstream(out / "result.h5") << "earlier result\n";
  std::vector<double> t(100000), u(100000);
  for (std::size_t k = 0; k < t.size(); ++k) t[k] = static_cast<double>(k) * 1e-4, u[k] = std::sin(static_cast<double>(k) * 1e-3);
  u[99000] = std::numeric_limits<double>::quiet_NaN();
  h5::write_file((dir() / "late.h5").string(), {{"/time", t, H5T_IEEE_F64LE, "s"}, {"/displacement", u, H5T_IEEE_F64LE, "mm"}});
  write_model(dir() / "late.rheo", "late.h5");
  const auto r = run_rheo(fmt::format("simulate '{}' -o '{}'", (dir() / "late.rheo").string(), (out / "result.h5").string()));
  CHECK(r.code == 4);
  CHECK(r.err.find((dir() / "late.h5").string() + ": error: /displacement[99000] (displacement) is nan;") != std::string::npos);
  CHECK(read(out / "result.h5") == "earlier result\n");
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(out)) ++files;
  CHECK(files == 1);
  // A harmonic result is not a history: said before anything runs.
  std::ofstream(dir() / "harmonic.rheo") << kModel << "simulate {\n  harmonic frequency = [1] Hz, amplitude = [0.5] mm\n}\n";
  const auto harmonic = run_rheo(fmt::format("simulate '{}' -o '{}'", (dir() / "harmonic.rheo").string(), (out / "h.h5").string()));
  CHECK(harmonic.code == 2);
  CHECK(harmonic.err.find("an HDF5 output holds a time history") != std::string::npos);
}

TEST_CASE("rheo fit fits an HDF5 history as it fits the same history as CSV") {
  // A measured history: the model's own result, as CSV and as HDF5.
  write_drive(dir() / "fit_drive.csv", 4000);
  write_model(dir() / "truth.rheo", "fit_drive.csv");
  REQUIRE(run_rheo(fmt::format("simulate '{}' -o '{}'", (dir() / "truth.rheo").string(), (dir() / "measured.csv").string())).code == 0);
  REQUIRE(run_rheo(fmt::format("simulate '{}' -o '{}'", (dir() / "truth.rheo").string(), (dir() / "measured.h5").string())).code == 0);
  std::ofstream(dir() / "start.rheo")
      << "model t {\n  spring e (k = 300 N/mm in [1, 10000])\n  maxwell m (k = 100 N/mm in [1, 10000], tau = 3 ms in [0.01, 10000])\n}\n";
  auto fit = [&](const std::string& data) {
    const auto r = run_rheo(fmt::format("fit '{}' --data '{}' --max-evaluations 40 --json", (dir() / "start.rheo").string(), (dir() / data).string()));
    CAPTURE(r.err);
    REQUIRE(r.code == 0);
    auto report = nlohmann::json::parse(r.out);
    report.erase("data");  // names the file
    return report;
  };
  const auto from_csv = fit("measured.csv"), from_h5 = fit("measured.h5");
  CHECK(from_csv["err"].get<double>() == from_h5["err"].get<double>());
  CHECK(from_csv["parameters"] == from_h5["parameters"]);
  // rheo report draws it, as it draws the CSV.
  const auto report = run_rheo(fmt::format("report '{}' --data '{}' -o '{}'", (dir() / "start.rheo").string(), (dir() / "measured.h5").string(),
                                           (dir() / "measured.html").string()));
  CAPTURE(report.err);
  CHECK(report.code == 0);
  CHECK(read(dir() / "measured.html").find("measured.h5") != std::string::npos);
}

TEST_CASE("a MATLAB v7.3 file drives a history and is fitted as the same history in HDF5: rheo writes .mat and fits it alike, v5 is refused") {
  // A struct's fields, a column vector in single precision, units on the line, against the CSV route.
  const std::vector<double> t{0.0, 1.0, 2.0, 3.0, 4.0, 5.0}, u{0.0, 100.0, 200.0, 150.0, 50.0, 0.0};  // ms and um
  mat::write_mat((dir() / "rig.mat").string(),
                 {{.path = "/rig/t", .values = t}, {.path = "/rig/u", .values = u, .matlab_class = "single", .type = H5T_IEEE_F32LE, .row = false}});
  std::ofstream(dir() / "rig_mat.csv") << "time [ms],displacement [um]\n0,0\n1,100\n2,200\n3,150\n4,50\n5,0\n";
  write_model(dir() / "rig_mat.rheo", "rig.mat", ", columns = \"time = rig.t [ms], displacement = /rig/u [um]\"");
  write_model(dir() / "rig_mat_csv.rheo", "rig_mat.csv");
  for (const std::string solver : {"fixed", "sundials"}) {
    CAPTURE(solver);
    const auto a = run_rheo(fmt::format("simulate '{}' --solver {}", (dir() / "rig_mat.rheo").string(), solver));
    CAPTURE(a.err);
    REQUIRE(a.code == 0);
    const auto b = run_rheo(fmt::format("simulate '{}' --solver {}", (dir() / "rig_mat_csv.rheo").string(), solver));
    REQUIRE(b.code == 0);
    CHECK(without_comments(a.out) == without_comments(b.out));
  }

  // A measured history as HDF5 (rheo's result) and the same doubles as MATLAB variables.
  write_drive(dir() / "mat_drive.csv", 3000);
  write_model(dir() / "mat_truth.rheo", "mat_drive.csv");
  const auto h5file = (dir() / "mat_measured.h5").string(), matfile = (dir() / "mat_measured.mat").string();
  REQUIRE(run_rheo(fmt::format("simulate '{}' -o '{}'", (dir() / "mat_truth.rheo").string(), h5file)).code == 0);
  mat::write_mat(matfile, {{.path = "/t", .values = h5::read_dataset(h5file, "/time")},
                           {.path = "/x", .values = h5::read_dataset(h5file, "/displacement"), .row = false},
                           {.path = "/F", .values = h5::read_dataset(h5file, "/force")}});
  std::ofstream(dir() / "mat_start.rheo") << "model t {\n  spring e (k = 300 N/mm in [1, 10000])\n  maxwell m (k = 100 N/mm in [1, 10000], tau = 3 "
                                             "ms in [0.01, 10000])\n}\n";
  auto fit = [&](const std::string& data) {
    const auto r = run_rheo(fmt::format("fit '{}' --data '{}' --max-evaluations 30 --json", (dir() / "mat_start.rheo").string(), data));
    CAPTURE(r.err);
    REQUIRE(r.code == 0);
    return nlohmann::json::parse(r.out);
  };
  const auto from_h5 = fit(h5file), from_mat = fit(matfile + ", columns = \"time = t [s], displacement = x [mm], force = F [N]\"");
  CHECK(from_h5["err"].get<double>() == from_mat["err"].get<double>());
  CHECK(from_h5["parameters"] == from_mat["parameters"]);
  // Without units, the advice names every variable with one.
  const auto bare = run_rheo(fmt::format("fit '{}' --data '{}'", (dir() / "mat_start.rheo").string(), matfile));
  CHECK(bare.code == 4);
  CHECK(bare.err.find(matfile + ": error: /t (time) has no unit: MATLAB saves none, and it has no 'units' attribute; write each variable's "
                                "unit after it: columns = \"time = t [s], displacement = x [mm], force = F [N]\"") != std::string::npos);
  // rheo report draws it.
  const auto report = run_rheo(fmt::format("report '{}' --data '{}' -o '{}'", (dir() / "mat_start.rheo").string(),
                                           matfile + ", columns = \"time = t [s], displacement = x [mm], force = F [N]\"",
                                           (dir() / "mat_measured.html").string()));
  CAPTURE(report.err);
  CHECK(report.code == 0);
  CHECK(read(dir() / "mat_measured.html").find("mat_measured.mat") != std::string::npos);

  // rheo's result written as a MAT-file (its variables carry 'units' attributes, so no columns
  // are needed) is fitted as the HDF5 one is; a harmonic result is not a history: refused before
  // anything runs. A v5 MAT-file as a history is refused.
  const auto out = run_rheo(fmt::format("simulate '{}' -o '{}'", (dir() / "mat_truth.rheo").string(), (dir() / "result.mat").string()));
  CAPTURE(out.err);
  REQUIRE(out.code == 0);
  const auto from_written = fit((dir() / "result.mat").string());
  CHECK(from_h5["err"].get<double>() == from_written["err"].get<double>());
  CHECK(from_h5["parameters"] == from_written["parameters"]);
  std::ofstream(dir() / "mat_harmonic.rheo") << "model m { spring (k = 10 N/mm) }\nsimulate {\n  harmonic frequency = [1] Hz, amplitude = [1] mm\n}\n";
  const auto harmonic = run_rheo(fmt::format("simulate '{}' -o '{}'", (dir() / "mat_harmonic.rheo").string(), (dir() / "harmonic.mat").string()));
  CHECK(harmonic.code == 2);
  CHECK(harmonic.err.find("harmonic.mat: a MATLAB output holds a time history") != std::string::npos);
  CHECK_FALSE(fs::exists(dir() / "harmonic.mat"));
  mat::write_v5_mat((dir() / "old.mat").string());
  write_model(dir() / "old.rheo", "old.mat");
  const auto old = run_rheo(fmt::format("simulate '{}'", (dir() / "old.rheo").string()));
  CHECK(old.code == 4);
  CHECK(old.err.find((dir() / "old.mat").string() + ": error: this is a MATLAB v5/v7 MAT-file (the default of save), which rheo cannot read; "
                                                    "re-save it as v7.3") != std::string::npos);
}

}  // namespace cli_hdf5_test
