// Fit data import (runtime/io/fit_data.hpp): the kind of a file is read from its header, values
// arrive in internal units, and a file that is neither kind, a history without force and an
// all-zero force are DataErrors that name the file (and row) and say what is needed.
#include "runtime/io/fit_data.hpp"

#include "hdf5_support.hpp"
#include "runtime/core/errors.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

namespace fit_data_test {

using namespace rheo;
namespace fs = std::filesystem;

namespace {

std::string write(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("rheo-fit-data-{}", ::getpid());
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return (dir / name).string();
}

std::string data_error(const std::string& path) {
  try {
    runtime::read_fit_data(path, 1.0);
  } catch (const runtime::DataError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("a table with amplitude and frequency is harmonic, in internal units, with its weight") {
  const auto path = write("harmonic.csv",
                          "# measured\namplitude [um],frequency [Hz],stiffness [kN/mm],phase [deg]\n200,1,1.4,17.5\n3000,51,0.7,12\n");
  const runtime::FitDataSet set = runtime::read_fit_data(path, 0.25);
  REQUIRE(set.is_harmonic());
  CHECK(set.path == path);
  CHECK(set.weight == 0.25);
  const auto& h = set.harmonic();
  REQUIRE(h.size() == 2);
  CHECK(h.amplitude[0] == doctest::Approx(0.2).epsilon(1e-15).scale(0.0));
  CHECK(h.amplitude[1] == doctest::Approx(3.0).epsilon(1e-15));
  CHECK(h.frequency[1] == 51.0);
  CHECK(h.stiffness[0] == doctest::Approx(1400.0).epsilon(1e-15));
  CHECK(h.phase[1] == doctest::Approx(12.0 * std::numbers::pi / 180.0).epsilon(1e-15).scale(0.0));
  CHECK(h.rows == std::vector<int>{3, 4});
}

TEST_CASE("a harmonic table may give storage and loss instead of stiffness and phase") {
  const auto path = write("storage.csv", "amplitude [mm],frequency [Hz],storage [N/mm],loss [N/mm]\n0.5,10,300,400\n");
  const auto set = runtime::read_fit_data(path, 1.0);
  REQUIRE(set.is_harmonic());
  CHECK(set.harmonic().stiffness[0] == doctest::Approx(500.0).epsilon(1e-15));
  CHECK(set.harmonic().phase[0] == doctest::Approx(std::atan2(4.0, 3.0)).epsilon(1e-15).scale(0.0));
}

TEST_CASE("a table with time, displacement and force is a history, its force scale is max |F|") {
  const auto path = write("history.csv", "time [ms],displacement [um],force [kN]\n0,0,0.01\n500,100,0.2\n1000,-300,-0.45\n");
  const runtime::FitDataSet set = runtime::read_fit_data(path, 2.0);
  REQUIRE_FALSE(set.is_harmonic());
  CHECK(set.weight == 2.0);
  const auto& h = set.history();
  CHECK(h.path == path);
  CHECK(h.drive.time == std::vector<double>{0.0, 0.5, 1.0});
  REQUIRE(h.drive.displacement.size() == 3);
  CHECK(h.drive.displacement[2] == doctest::Approx(-0.3).epsilon(1e-15).scale(0.0));
  REQUIRE(h.force.size() == 3);
  CHECK(h.force[1] == doctest::Approx(200.0).epsilon(1e-15));
  CHECK(h.force_scale == doctest::Approx(450.0).epsilon(1e-15));
  CHECK(h.rows == std::vector<int>{2, 3, 4});
}

TEST_CASE("a table that is neither kind: the message names the file, lists the columns each kind needs and the header's") {
  const auto path = write("neither.csv", "strain [-],stress [N]\n0,0\n0.1,5\n");
  const std::string message = data_error(path);
  CAPTURE(message);
  CHECK(message.rfind(path + ":1:1: error:", 0) == 0);  // at the header
  for (const char* column : {"'amplitude'", "'frequency'", "'stiffness'", "'phase'", "'storage'", "'loss'", "'time'", "'displacement'", "'force'"})
    CHECK(contains(message, column));
  CHECK(contains(message, "the header has: strain, stress"));
}

TEST_CASE("a history without a force column names the file and the column to add") {
  const auto path = write("noforce.csv", "time [s],displacement [mm]\n0,0\n1,0.5\n");
  const std::string message = data_error(path);
  CAPTURE(message);
  CHECK(message.rfind(path + ":1:1: error:", 0) == 0);
  CHECK(contains(message, "'force [N]'"));
  CHECK(contains(message, "the header has: time, displacement"));
}

TEST_CASE("a history whose force is zero throughout names the file and its first data row") {
  const auto path = write("zero.csv", "# no signal\n\ntime [s],displacement [mm],force [N]\n0,0,0\n1,0.5,0\n2,0,-0\n");
  const std::string message = data_error(path);
  CAPTURE(message);
  CHECK(message.rfind(path + ":4:5: error:", 0) == 0);  // the first force cell
  CHECK(contains(message, "zero"));
}

TEST_CASE("a harmonic table lacking a needed column says so at the header, a history from a displacement is read as it is") {
  const auto no_phase = write("nophase.csv", "amplitude [mm],frequency [Hz],stiffness [N/mm]\n0.5,10,300\n");
  const std::string phase_message = data_error(no_phase);
  CAPTURE(phase_message);
  CHECK(phase_message.rfind(no_phase + ":1:1: error:", 0) == 0);
  CHECK(contains(phase_message, "'phase'"));
  const auto moving = write("moving.csv", "time [s],displacement [mm],force [N]\n0,0.2,1\n1,0.5,2\n");
  const auto set = runtime::read_fit_data(moving, 1.0);
  CHECK(set.history().drive.displacement == std::vector<double>{0.2, 0.5});
}

TEST_CASE("a missing file is a DataError naming it") {
  const std::string message = data_error("/nonexistent/rheo/fit-data.csv");
  CHECK(message.rfind("/nonexistent/rheo/fit-data.csv: error:", 0) == 0);
}

TEST_CASE("an HDF5 file is a measured history, the same as its CSV twin: settings of other kinds are refused") {
  const std::string csv = write("twin.csv", "time [ms],displacement [um],force [kN]\n0,0,0\n1,100,0.5\n2,300,1.25\n");
  const std::string h5 = fs::path(csv).replace_extension(".h5").string();
  rheo::test::hdf5::write_file(h5, {{"/rig/t", {0, 1, 2}, H5T_STD_I16LE, "ms"},
                                    {"/rig/u", {0, 100, 300}, H5T_IEEE_F32LE, "um"},
                                    {"/rig/F", {0, 0.5, 1.25}, H5T_IEEE_F64LE, "kN"}});
  runtime::DataReading reading;
  reading.columns.columns = {{runtime::Role::time, "rig/t"}, {runtime::Role::displacement, "/rig/u"}, {runtime::Role::force, "/rig/F"}};
  const auto from_h5 = runtime::read_fit_data(h5, 0.5, nullptr, reading);
  const auto from_csv = runtime::read_fit_data(csv, 0.5);
  REQUIRE_FALSE(from_h5.is_harmonic());
  CHECK(from_h5.weight == 0.5);
  CHECK(from_h5.history().drive.time == from_csv.history().drive.time);
  CHECK(from_h5.history().drive.displacement == from_csv.history().drive.displacement);
  CHECK(from_h5.history().force == from_csv.history().force);
  CHECK(from_h5.history().force_scale == 1250.0);
  reading.step = "Ramp";
  CHECK_THROWS_WITH_AS(
      runtime::read_fit_data(h5, 1.0, nullptr, reading),
      (h5 + ": error: an HDF5 file is read as a history, so the data line's step (of a TRIOS export) does not apply; remove it").c_str(),
      runtime::DataError);
}

TEST_CASE("a CSV history is streamed into arrays: the same history, rows and faults as the table read whole") {
  std::string text = "# rig 3\ntime [ms];displacement [um];force [kN];note\n";
  for (int k = 0; k < 30000; ++k) text += fmt::format("{};{};{};{}\n", k * 0.5, 1e3 * std::sin(k * 1e-3), std::cos(k * 2e-3), k % 2 ? "ok" : "x,y");
  const auto path = write("long.csv", text);
  const auto streamed = runtime::stream_measured_history(path, nullptr, {});
  REQUIRE(streamed.has_value());
  const runtime::HistoryData whole = runtime::history_data_from_table(runtime::read_table(path));
  CHECK(streamed->drive.time == whole.drive.time);  // exactly: the same cells read by the same code
  CHECK(streamed->drive.displacement == whole.drive.displacement);
  CHECK(streamed->force == whole.force);
  CHECK(streamed->rows == whole.rows);
  CHECK(streamed->force_scale == whole.force_scale);
  CHECK(runtime::read_fit_data(path, 1.0).history().force == whole.force);
  // A fault late in the file: the whole-file message.
  const auto late = write("late.csv", text + "15000;1;1,5;z\n15001;2;NaN;z\n");
  std::string whole_error;
  try {
    (void)runtime::history_data_from_table(runtime::read_table(late));
  } catch (const runtime::DataError& e) {
    whole_error = e.what();
  }
  CHECK(whole_error == fmt::format("{}:30004:9: error: 'NaN' is not a finite number (column 'force'); remove or repair the row", late));
  CHECK(data_error(late) == whole_error);
  // The bound is on the samples held, said before more are held.
  CHECK_THROWS_WITH_AS(runtime::stream_measured_history(path, nullptr, {}, 20000),
                       (path + ": error: the history has more than 20000 samples, the most a fit or report holds (512 MiB at 24 bytes a sample); "
                               "fit a part of it, or resample it")
                           .c_str(),
                       runtime::DataError);
  CHECK(runtime::stream_measured_history(path, nullptr, {}, 30000).has_value());
}

TEST_CASE("files that are not streamed histories are left to whole-file reading") {
  const auto harmonic = write("sweep.csv", "amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n0.5,10,300,10\n");
  CHECK_FALSE(runtime::stream_measured_history(harmonic, nullptr, {}).has_value());
  const auto no_force = write("drive.csv", "time [s],displacement [mm]\n0,0\n1,1\n");
  CHECK_FALSE(runtime::stream_measured_history(no_force, nullptr, {}).has_value());
  const auto header_only = write("header.csv", "time [s],displacement [mm],force [N]\n");
  CHECK_FALSE(runtime::stream_measured_history(header_only, nullptr, {}).has_value());
  const auto wide = write("wide.csv", "time [s],displacement [mm],force [N]\n0,0,1,4\n1,1,1\n");
  CHECK_FALSE(runtime::stream_measured_history(wide, nullptr, {}).has_value());
  CHECK(contains(data_error(wide), ":2:7: error: this row has 4 values, the header has 3 columns"));
  runtime::DataReading named;
  named.columns.columns = {{runtime::Role::force, "F"}};  // a column the header lacks: the whole-file message
  CHECK_FALSE(runtime::stream_measured_history(no_force, nullptr, named).has_value());
  CHECK_FALSE(runtime::stream_measured_history("/dev/null", nullptr, {}).has_value());
  CHECK_FALSE(runtime::stream_measured_history(RHEO_DATA_DIR, nullptr, {}).has_value());
}

TEST_CASE("SampleRows holds runs of consecutive lines: every row back by index, equal rows equal, memory by the runs") {
  // Lines 3-6, a comment line, 8-9, a row repeated (an HDF5 index clamped), then 20.
  const std::vector<int> lines{3, 4, 5, 6, 8, 9, 9, 20};
  runtime::SampleRows rows;
  rows.append({3, 4, 5});
  for (std::size_t k = 3; k < lines.size(); ++k) rows.push_back(lines[k]);
  CHECK(rows.size() == lines.size());
  CHECK(rows == lines);
  for (std::size_t k = 0; k < lines.size(); ++k) CHECK(rows[k] == lines[k]);
  CHECK(rows.front() == 3);
  CHECK(rows.runs() == 4);  // 3-6, 8-9, 9, 20
  CHECK_THROWS_AS((void)rows[lines.size()], std::out_of_range);
  CHECK(rows == runtime::SampleRows{3, 4, 5, 6, 8, 9, 9, 20});
  CHECK_FALSE(rows == runtime::SampleRows{3, 4, 5, 6, 7, 9, 9, 20});
  // A million consecutive lines are one run.
  runtime::SampleRows many;
  for (int line = 2; line < 1'000'002; ++line) many.push_back(line);
  CHECK(many.size() == 1'000'000);
  CHECK(many.runs() == 1);
  CHECK(many[999'999] == 1'000'001);
  CHECK(many == runtime::SampleRows(many));
  runtime::SampleRows same;
  same.assign(3, 0);
  CHECK(same == std::vector<int>{0, 0, 0});
  same.clear();
  CHECK(same.empty());
}

}  // namespace fit_data_test
