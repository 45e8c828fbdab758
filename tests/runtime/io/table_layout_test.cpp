// Tables as instruments write them: delimiters, decimal commas, units rows, TRIOS steps,
// workbooks and UTF-16.
#include "runtime/io/table_layout.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/io/fit_data.hpp"
#include "runtime/io/history_csv.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

namespace table_layout_test {

using namespace rheo::runtime;
using namespace std::string_literals;

namespace {
const std::string trios = std::string(RHEO_DATA_DIR) + "/real/trios_multi_technique.txt";

std::string error_of(const std::string& text, const std::string& path = "t.csv", const std::string& step = "") {
  try {
    parse_table(path, text, step);
  } catch (const DataError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("the delimiter is the one the names row uses most: tab, then semicolon, then comma") {
  CHECK(detect_delimiter("a,b,c") == ',');
  CHECK(detect_delimiter("a;b;c") == ';');
  CHECK(detect_delimiter("a\tb\tc") == '\t');
  CHECK(detect_delimiter("f [Hz];E' [MPa],x;y") == ';');
  CHECK(detect_delimiter("\"a;b\",c") == ',');  // inside quotes a delimiter is text
  CHECK(detect_delimiter("time") == ',');
  std::vector<Cell> cells;
  std::string scratch;
  split_cells("\"Storage, modulus\" , \"say \"\"hi\"\"\",3", ',', cells, scratch);
  REQUIRE(cells.size() == 3);
  CHECK(cells[0].text == "Storage, modulus");
  CHECK(cells[1].text == "say \"hi\"");
  CHECK(cells[2].text == "3");
  CHECK(cells[2].column == 35);
}

TEST_CASE("semicolon and tab tables take a decimal comma, comma tables do not") {
  const Table semicolon = parse_table("t.csv", "Time [s];Displacement [mm]\n0;0\n0,5;1,25\n");
  CHECK(semicolon.columns[0][1] == 0.5);
  CHECK(semicolon.columns[1][1] == 1.25);
  const Table tab = parse_table("t.txt", "time [ms]\tforce [kN]\n1,5\t+2,0E-1\n");
  CHECK(tab.columns[0][0] == doctest::Approx(1.5e-3).scale(0.0));
  CHECK(tab.columns[1][0] == doctest::Approx(200.0));
  const Table comma = parse_table("t.csv", "time [s],x\n1,2\n");
  CHECK(comma.columns[0][0] == 1.0);
  CHECK(comma.columns[1][0] == 2.0);
}

TEST_CASE("units in brackets, in parentheses when they are units, or in a units row under the names") {
  const Table parentheses = parse_table("t.csv", "Frequency (Hz),Storage Modulus (MPa),Stress (step)\n1,2,3\n");
  CHECK(parentheses.names[0] == "Frequency");
  CHECK(parentheses.units[1] == "MPa");
  CHECK(parentheses.names[2] == "Stress (step)");  // '(step)' is no unit: part of the name
  CHECK(parentheses.units[2].empty());
  const Table units_row = parse_table("dma.csv", "f;E_stor;E_loss;note\nHz;MPa;kPa;\n1;2,5;30;ok\n");
  CHECK(units_row.units_row == 2);
  CHECK(units_row.names[1] == "E_stor");
  CHECK(units_row.units[2] == "kPa");
  CHECK(units_row.columns[1][0] == 2.5);                               // MPa is N/mm^2
  CHECK(units_row.columns[2][0] == doctest::Approx(0.03).scale(0.0));  // 30 kPa
  CHECK(units_row.rows == std::vector<int>{3});
  // Without units anywhere the first row is data.
  const Table plain = parse_table("t.csv", "a,b\n1,2\n");
  CHECK(plain.units_row == 0);
  CHECK(plain.rows.size() == 1);
  CHECK(table_unit("\xC2\xB5m")->scale == doctest::Approx(1e-3).scale(0.0));  // µm
  CHECK(table_unit("\xC2\xB0")->scale == doctest::Approx(M_PI / 180.0).scale(0.0));
  CHECK(table_unit("%")->scale == 0.01);
  CHECK(table_unit("N/mm\xC2\xB2")->dimension == rheo::lang::dim::pressure);
  CHECK_FALSE(table_unit("\xC2\xB0"
                         "C")
                  .has_value());
}

TEST_CASE("a TRIOS export: each [step] is a table with names and units rows, the data line picks one") {
  const Table amplitude = read_table(trios, nullptr, "Amplitude sweep");
  CHECK(amplitude.step == "Amplitude sweep - 1");
  CHECK(amplitude.names.size() == 43);
  CHECK(amplitude.rows.size() == 29);
  CHECK(amplitude.header_row == 168);
  CHECK(amplitude.units_row == 169);
  const int strain = amplitude.column("oscillation STRAIN");
  REQUIRE(strain >= 0);
  CHECK(amplitude.units[static_cast<std::size_t>(strain)] == "%");
  CHECK(amplitude.columns[static_cast<std::size_t>(strain)][0] == doctest::Approx(0.00989877906867619 * 0.01).scale(0.0));
  const Table frequency = read_table(trios, nullptr, "frequency sweep - 2");
  CHECK(frequency.step == "Frequency sweep - 2");
  CHECK(frequency.rows.front() == 204);
  CHECK_THROWS_WITH_AS(read_table(trios),
                       doctest::Contains("this TRIOS export has 3 steps (\"Amplitude sweep - 1\", \"Frequency sweep - 2\", "
                                         "\"Flow ramp - 3\"); pick the one to read on the data line, e.g. step = \"Amplitude sweep\""),
                       DataError);
  CHECK_THROWS_WITH_AS(read_table(trios, nullptr, "Creep"), doctest::Contains("has no step \"Creep\"; its steps are"), DataError);
  CHECK(error_of("time [s],x\n0,0\n", "t.csv", "Amplitude sweep").find("t.csv:1:1: error: step = \"Amplitude sweep\" picks a step of a TRIOS export") ==
        0);
  // One step: no need to name it.
  CHECK(parse_table("one.txt", "[step]\nRamp - 1\nTime\tForce\ns\tN\n0\t1\n\n").rows.size() == 1);
}

TEST_CASE("spreadsheet workbooks are refused with what to do, UTF-16 text is read") {
  CHECK(error_of("PK\x03\x04rest"s, "sweep.csv").find("sweep.csv:1:1: error: this is a spreadsheet workbook, not a text table; export the sheet as CSV") ==
        0);
  CHECK(error_of("\xD0\xCF\x11\xE0 rest"s, "old.dat").find("old.dat:1:1: error: this is a spreadsheet workbook") == 0);
  CHECK(error_of("time [s]\n0\n", "sweep.xlsx").find("sweep.xlsx:1:1: error: this is a spreadsheet workbook") == 0);
  // An HDF5 file under a text table's name: said so, with the name rheo reads HDF5 by.
  CHECK(error_of("\x89HDF\r\n\x1a\n\0\0"s, "run.csv")
            .find("run.csv:1:1: error: this is an HDF5 file, not a text table; rheo reads HDF5 histories from "
                  "files named .h5 or .hdf5: rename it") == 0);
  // MATLAB files under a text table's name: a v7.3 one (HDF5 behind MATLAB's text header) is read
  // when named .mat, a v5 one not at all.
  CHECK(error_of("MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Fri Nov 27 08:00:00 2026 HDF5 schema 1.00 .  \0\x02IM"s, "run.csv") ==
        "run.csv:1:1: error: this is a MATLAB v7.3 MAT-file, not a text table; rheo reads one as a history when its name ends in .mat: rename "
        "it (docs/data-formats.md, \"MATLAB files\")");
  CHECK(error_of("MATLAB 5.0 MAT-file, Platform: PCWIN64, Created on: Fri Nov 27 08:00:00 2026  \0\x01IM"s, "run.txt") ==
        "run.txt:1:1: error: this is a MATLAB v5/v7 MAT-file, not a text table; re-save it in MATLAB as v7.3 and name it .mat "
        "(save('run.mat', 't', 'x', 'F', '-v7.3')), or export the history as a CSV table");
  std::string utf16 = "\xFF\xFE"s;
  for (char c : "time [\xC2\xB5s],displacement [mm]\n0,0\n1,2\n"s) {
    if (c == '\xC2') continue;
    utf16 += c == '\xB5' ? "\xB5\0"s : std::string(1, c) + '\0';
  }
  const Table t = parse_table("w.csv", utf16);
  CHECK(t.units[0] == "\xC2\xB5s");
  CHECK(t.columns[0][1] == doctest::Approx(1e-6).scale(0.0));
  CHECK(t.columns[1][1] == 2.0);
}

}  // namespace table_layout_test
