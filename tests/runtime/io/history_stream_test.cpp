// The streamed history reader against the whole-file one (two paths over the same text): for
// sound tables the same drive, sample for sample and bit for bit, whatever the block size; for
// faulty ones the same message at the same file:row:column, however late in the file the fault
// sits and whatever other faults follow or precede it; measured histories (force too) alike.
#include "runtime/io/history_stream.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/io/fit_data.hpp"
#include "runtime/io/history_csv.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace history_stream_test {

using namespace rheo::runtime;
using namespace std::string_literals;

namespace {

struct Reading {
  std::vector<double> time, displacement, force;
  std::vector<int> rows;
  std::string error;  // the DataError's message; "" when none
  bool not_streamable = false;
  std::size_t pieces = 0, largest_piece = 0;
};

bool operator==(const Reading& a, const Reading& b) {
  auto same = [](const std::vector<double>& x, const std::vector<double>& y) {
    return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0);
  };
  return a.error == b.error && same(a.time, b.time) && same(a.displacement, b.displacement) && same(a.force, b.force) && a.rows == b.rows;
}

// TEXT through HistoryStream, BLOCK bytes read at a time; WITH_FORCE: as a measured history
// (time, displacement, force).
Reading streamed(const std::string& text, bool from_rest, std::size_t block, bool with_force = false) {
  std::FILE* file = std::tmpfile();
  REQUIRE(file != nullptr);
  std::fwrite(text.data(), 1, text.size(), file);
  std::rewind(file);
  Reading r;
  try {
    HistoryStream stream("t.csv", file, from_rest, block);
    if (with_force) stream.read_force();
    DrivePiece piece;
    std::vector<double> force;
    while (stream.next(piece, with_force ? &force : nullptr)) {
      if (with_force) REQUIRE(force.size() == piece.time.size());
      ++r.pieces;
      r.largest_piece = std::max(r.largest_piece, piece.time.size());
      r.time.insert(r.time.end(), piece.time.begin(), piece.time.end());
      r.displacement.insert(r.displacement.end(), piece.displacement.begin(), piece.displacement.end());
      r.force.insert(r.force.end(), force.begin(), force.end());
      r.rows.insert(r.rows.end(), piece.rows.begin(), piece.rows.end());
    }
  } catch (const DataError& e) {
    r = Reading{};
    r.error = e.what();
  } catch (const NotStreamable&) {
    r = Reading{};
    r.not_streamable = true;
  }
  return r;
}

// TEXT read whole, as `history` protocols read files before #28.
Reading whole(const std::string& text, bool from_rest) {
  Reading r;
  try {
    const Table table = parse_table("t.csv", text);
    const Drive d = drive_from_table(table, from_rest);
    r.time = d.time, r.displacement = d.displacement, r.rows = table.rows;
  } catch (const DataError& e) {
    r.error = e.what();
  }
  return r;
}

void check_alike(const std::string& text, bool from_rest = false) {
  CAPTURE(text);
  const Reading expected = whole(text, from_rest);
  for (const std::size_t block : {std::size_t{4}, std::size_t{7}, std::size_t{64}, HistoryStream::kBlockBytes}) {
    CAPTURE(block);
    const Reading got = streamed(text, from_rest, block);
    CHECK_FALSE(got.not_streamable);
    CHECK(got.error == expected.error);
    CHECK(got == expected);
  }
}

// A history table of N rows with random faults and layout variants (seeded).
std::string random_table(std::mt19937& random, int n) {
  auto pick = [&](int k) { return static_cast<int>(random() % static_cast<unsigned>(k)); };
  const bool semicolon = pick(4) == 0;
  const char sep = semicolon ? ';' : ',';
  std::string text = pick(8) == 0 ? "\xEF\xBB\xBF" : "";
  if (pick(3) == 0) text += "# a rig's notes\n\n";
  const std::vector<std::string> headers = {fmt::format("time [s]{}displacement [mm]", sep),
                                            fmt::format("Time (ms){}Position (um){}force [N]", sep, sep),
                                            fmt::format("time{}displacement\ns{}mm", sep, sep),
                                            fmt::format("time [s]{}displacement [furlong]", sep),
                                            fmt::format("time [s]{}force [N]", sep),
                                            fmt::format("time [s]{}displacement", sep),
                                            fmt::format("\"time [s]\"{}\"displacement [mm]\"", sep),
                                            fmt::format("t [s]{}displacement [mm]{}time [s]", sep, sep)};
  text += headers[static_cast<std::size_t>(pick(8) < 6 ? 0 : pick(static_cast<int>(headers.size())))] + (pick(6) == 0 ? "\r\n" : "\n");
  double t = pick(2) ? 0.0 : 1.5;
  // Faults of one or two kinds (0 to 4, 7, 8, 11, 12), in one row of 20 on average, or none.
  const std::vector<int> faults = {0, 1, 2, 3, 4, 7, 8, 11, 12};
  const int none = pick(3) == 0 ? 1 : 0, first = faults[static_cast<std::size_t>(pick(9))],
            second = pick(4) == 0 ? faults[static_cast<std::size_t>(pick(9))] : first;
  for (int k = 0; k < n; ++k) {
    t += 0.001 * (1 + pick(3));
    std::string time = fmt::format("{}", t), disp = fmt::format("{}", std::sin(t) * 2.0);
    if (semicolon) {
      for (char& c : time) c = c == '.' ? ',' : c;
      for (char& c : disp) c = c == '.' ? ',' : c;
    }
    std::string line = time + sep + disp;
    const int variants[] = {5, 6, 9, 10, 13};
    int kind = pick(20) == 0 ? variants[pick(5)] : -1;
    if (!none && pick(20) == 0) kind = pick(2) ? first : second;
    switch (kind) {
      case 0: line = time + sep + "NaN"; break;
      case 1: line = time + sep; break;
      case 2: line = time + sep + disp + sep + "7" + sep + "8"; break;
      case 3: line = "0" + std::string(1, sep) + disp; break;  // time backwards
      case 4: line = time + sep + "1e30"; break;               // beyond a rig
      case 5: line = "# comment " + line; break;
      case 6: line = ""; break;
      case 7: line = time + sep + "\xff"; break;  // not UTF-8
      case 8: line = time + sep + "1\0"s; break;  // a NUL byte
      case 9: line = time + sep + "+" + disp; break;
      case 10: line = "\"" + time + "\"" + sep + disp; break;
      case 11: line = time + sep + "abc"; break;
      case 12: line = time + sep + "1e400"; break;
      case 13: line = "  " + time + " " + sep + " " + disp + "\t"; break;
      default: break;
    }
    text += line + (pick(6) == 0 ? "\r\n" : "\n");
  }
  if (pick(4) == 0 && !text.empty()) text.pop_back();  // no line end after the last row
  return text;
}

}  // namespace

TEST_CASE("sound tables: the streamed drive is the whole-file drive bit for bit, rows too, for any block size") {
  check_alike("time [s],displacement [mm]\n0,0\n0.1,0.5\n0.2,1\n");
  check_alike("\xEF\xBB\xBF# rig 4\n\nTime (ms);Position (um)\r\n1,5;+2,0E-1\r\n2,5;3\r\n");
  check_alike("time,displacement\ns,mm\n1,1\n2,2\n3,3");  // a units row, no final line end
  check_alike("\"time [s]\",\"displacement [mm]\"\n\"0\",\"0.25\"\n\"1\",0.5\n");
  check_alike("time [s],displacement [mm],force [N]\n0,0\n1,2\n");  // short rows: force is not read
  check_alike("time [s],displacement [mm]\n0,0\n0.5,1e-3\n", true);
}

TEST_CASE("faulty tables: the streamed reader fails with the whole-file reader's message, whichever fault comes first") {
  check_alike("");
  check_alike("# only notes\n");
  check_alike("time [s],displacement [mm]\n");
  check_alike("time [s],displacement [mm]\n0,0\n");
  check_alike("time [s],force [N]\n0,0\n1,1\n");
  check_alike("time [s],displacement [mm]\n0,0\n1,NaN\n2,x\n");
  check_alike("time [s],displacement [furlong]\n0,0\n1,1\n");
  check_alike("time [s],displacement\n0,0\n1,1\n");
  check_alike("time [s],displacement [mm]\n0,0\n1,1\n1,2\n");
  check_alike("time [s],displacement [mm]\n0,0\n1,1e30\n");
  check_alike("time [s],displacement [mm]\n0,0.5\n1,1\n", true);
  // Later faults that whole-file reading reports first: a bad cell of time after a bad cell of
  // displacement, a row too wide after both, bytes that are not text after everything.
  check_alike("time [s],displacement [mm]\n0,0\n1,NaN\n2,2\nx,3\n");
  check_alike("time [s],displacement [mm]\n0,0\n1,NaN\nx,3\n4,4,4\n");
  check_alike("time [s],displacement [mm]\n0,0\n0,NaN\n4,4,4\n5,\xff\n");
  // start = rest is judged against the largest displacement of the whole history.
  check_alike("time [s],displacement [mm]\n0,1e-12\n1,1e-2\n2,1\n", true);
  check_alike("time [s],displacement [mm]\n0,1e-12\n1,1e-4\n2,1e-3\n", true);
  check_alike("time [s],displacement [mm]\n0,1e-9\n0,1e-4\n2,1e-3\n", true);
  check_alike("time [s],displacement [mm]\n0,1e30\n");
}

TEST_CASE("random tables with random faults read alike streamed and whole, for block sizes down to 4 bytes") {
  std::mt19937 random(28);
  int faulty = 0, sound = 0;
  for (int k = 0; k < 400; ++k) {
    const std::string text = random_table(random, 1 + static_cast<int>(random() % 60));
    const bool from_rest = random() % 5 == 0;
    check_alike(text, from_rest);
    (whole(text, from_rest).error.empty() ? sound : faulty) += 1;
  }
  MESSAGE(sound << " sound and " << faulty << " faulty tables");
  CHECK(sound >= 40);  // both kinds are exercised
  CHECK(faulty >= 40);
}

TEST_CASE("a fault late in a long file is found at its row and column after many pieces were handed out") {
  std::string text = "time [s],displacement [mm]\n";
  constexpr int rows = 200000;
  for (int k = 0; k < rows; ++k) text += k == 180000 ? fmt::format("{},NaN\n", k * 1e-4) : fmt::format("{},{}\n", k * 1e-4, std::sin(k * 1e-3));
  std::FILE* file = std::tmpfile();
  std::fwrite(text.data(), 1, text.size(), file);
  std::rewind(file);
  HistoryStream stream("long.csv", file, false, 1 << 16);
  DrivePiece piece;
  std::size_t handed = 0;
  std::string error;
  try {
    while (stream.next(piece)) handed += piece.time.size();
  } catch (const DataError& e) {
    error = e.what();
  }
  CHECK(handed > 100000);  // the pieces before the fault came out, each bounded by the block
  CHECK(handed < 180000);
  CHECK(error == fmt::format("long.csv:180002:{}: error: 'NaN' is not a finite number (column 'displacement'); remove or repair the row",
                             fmt::format("{}", 180000 * 1e-4).size() + 2));
}

TEST_CASE("pieces are bounded by the block read, however long the file") {
  std::string text = "time [s],displacement [mm]\n";
  for (int k = 0; k < 50000; ++k) text += fmt::format("{},{}\n", k, k % 7);
  const Reading r = streamed(text, false, 4096);
  REQUIRE(r.error.empty());
  CHECK(r.time.size() == 50000);
  CHECK(r.pieces > 50);
  CHECK(r.largest_piece <= 4096 / 4);  // a data row is at least "0,0\n"
  CHECK(r.time.back() == 49999.0);
}

TEST_CASE("files the stream does not take are left to whole-file reading: devices and pipes, UTF-16, TRIOS exports, a names row of CRs") {
  CHECK_THROWS_AS(HistoryStream("/dev/zero", static_cast<const rheo::lang::SourceLocation*>(nullptr), false), NotStreamable);
  CHECK(streamed("\xFF\xFEt\0i\0m\0e\0"s, false, 64).not_streamable);
  CHECK(streamed("time [s],displacement [mm]\n0,0\n1,1\n[step]\nx\n", false, 8).not_streamable);
  CHECK(streamed("\r\r\ntime [s],displacement [mm]\n0,0\n1,1\n", false, 8).not_streamable);
  CHECK(streamed("time [s],displacement [mm]\n0,0\n1," + std::string(300, '1') + "\n", false, 64).error.find("beyond") != std::string::npos);
}

TEST_CASE("a workbook and a directory fail as whole-file reading fails") {
  CHECK(streamed("PK\x03\x04rest", false, 64).error == whole("PK\x03\x04rest", false).error);
  // MATLAB's signature is 19 bytes: a stream read 7 bytes at a time still sees all of it.
  for (const std::string& mat : {"MATLAB 7.3 MAT-file, Platform: GLNXA64\n0,0\n"s, "MATLAB 5.0 MAT-file\n0,0\n"s}) {
    CHECK(streamed(mat, false, 7).error == whole(mat, false).error);
    CHECK(streamed(mat, false, 7).error.find("MAT-file") != std::string::npos);
  }
  CHECK_THROWS_WITH_AS(HistoryStream(RHEO_DATA_DIR, static_cast<const rheo::lang::SourceLocation*>(nullptr), false),
                       doctest::Contains("cannot read the file (it is a directory)"), DataError);
  CHECK_THROWS_WITH_AS(HistoryStream("/nonexistent/h.csv", static_cast<const rheo::lang::SourceLocation*>(nullptr), false),
                       doctest::Contains("No such file"), DataError);
}

namespace {

// TEXT read whole into a measured history, as fits read CSV histories before #28.
Reading whole_measured(const std::string& text) {
  Reading r;
  try {
    const HistoryData h = history_data_from_table(parse_table("t.csv", text));
    r.time = h.drive.time, r.displacement = h.drive.displacement, r.force = h.force, r.rows = h.rows.all();
  } catch (const DataError& e) {
    r.error = e.what();
  }
  return r;
}

void check_measured_alike(const std::string& text) {
  CAPTURE(text);
  const Reading expected = whole_measured(text);
  for (const std::size_t block : {std::size_t{4}, std::size_t{9}, std::size_t{64}, HistoryStream::kBlockBytes}) {
    CAPTURE(block);
    const Reading got = streamed(text, false, block, true);
    CHECK_FALSE(got.not_streamable);
    CHECK(got.error == expected.error);
    CHECK(got == expected);
  }
}

// A measured history of N rows (time, displacement, force; in any order of columns) with
// random faults in any of them (seeded).
std::string random_measured_table(std::mt19937& random, int n) {
  auto pick = [&](int k) { return static_cast<int>(random() % static_cast<unsigned>(k)); };
  const std::vector<std::string> headers = {
      "time [s],displacement [mm],force [N]",  "force [kN],time [ms],displacement [um]", "t,x,F\ns,mm,N",
      "time [s],displacement [mm],force [mm]", "time [s],displacement [mm],load",        "time [s],displacement [mm],force [N],note"};
  const int header = pick(4) < 3 ? 0 : pick(static_cast<int>(headers.size()));
  std::string text = headers[static_cast<std::size_t>(header)] + "\n";
  const bool force_first = header == 1, note = header == 5, zero = pick(8) == 0;
  double t = 0.0;
  const int fault = pick(3) == 0 ? -1 : pick(8);
  for (int k = 0; k < n; ++k) {
    t += 0.001 * (1 + pick(3));
    std::string time = fmt::format("{}", t), disp = fmt::format("{}", std::sin(t) * 2.0), force = zero ? "0" : fmt::format("{}", std::cos(t) * 3.0);
    if (fault >= 0 && pick(15) == 0) {
      switch (fault) {
        case 0: force = "NaN"; break;
        case 1: force = ""; break;
        case 2: force = "12 N"; break;
        case 3: disp = "x"; break;
        case 4: time = "0"; break;
        case 5: force = "1e400"; break;
        case 6: force = "0"; break;
        default: force += ",1,2"; break;
      }
    }
    text += (force_first ? force + "," + time + "," + disp : time + "," + disp + "," + force) + (note ? ",n/a" : "") + "\n";
  }
  return text;
}

}  // namespace

TEST_CASE("a measured history streamed with its force reads as the whole-file reader reads it, faults alike") {
  check_measured_alike("time [s],displacement [mm],force [N]\n0,0,1\n0.1,0.5,2\n0.2,1,-3\n");
  check_measured_alike("force [kN];Time (ms);Position (um)\n1,5;0;2\n2;1;3\n");
  check_measured_alike("t,x,F,Temperature\ns,mm,N,degC\n0,0,1,20\n1,1,2,twenty\n");  // a column no reader uses is not checked
  // Faults: no force column, force's unit, a bad force cell, force zero everywhere; and drive
  // faults, which whole-file reading reports before the force's.
  check_measured_alike("time [s],displacement [mm]\n0,0\n1,1\n");
  check_measured_alike("time [s],displacement [mm],force [mm]\n0,0,1\n1,1,1\n");
  check_measured_alike("time [s],displacement [mm],force\n0,0,1\n1,1,1\n");
  check_measured_alike("time [s],displacement [mm],force [N]\n0,0,1\n1,1,NaN\n2,2,3\n");
  check_measured_alike("time [s],displacement [mm],force [N]\n0,0,1\n1,1\n2,2,3\n");
  check_measured_alike("time [s],displacement [mm],force [N]\n0,0,0\n1,1,0\n2,2,0\n");
  check_measured_alike("time [s],displacement [mm],force [N]\n0,0,0\n1,1,0\n1,2,0\n");
  check_measured_alike("time [s],displacement [mm],force [N]\n0,0,1\n1,1,NaN\n1,2,3\n");
  check_measured_alike("time [s],displacement [mm],force [N]\n0,0,x\n1,NaN,1\n");
  check_measured_alike("time [s],displacement [mm],force [N]\n0,0,1\n");
  std::mt19937 random(2828);
  int faulty = 0, sound = 0;
  for (int k = 0; k < 300; ++k) {
    const std::string text = random_measured_table(random, 1 + static_cast<int>(random() % 50));
    check_measured_alike(text);
    (whole_measured(text).error.empty() ? sound : faulty) += 1;
  }
  MESSAGE(sound << " sound and " << faulty << " faulty measured tables");
  CHECK(sound >= 40);
  CHECK(faulty >= 40);
}

TEST_CASE("the header and first rows are read before any piece, to tell a table's kind") {
  std::FILE* file = std::tmpfile();
  const std::string text = "# notes\nfrequency [Hz],amplitude [mm],stiffness [N/mm],phase [deg]\n1,0.1,100,10\n2,0.1,110,11\n";
  std::fwrite(text.data(), 1, text.size(), file);
  std::rewind(file);
  HistoryStream stream("h.csv", file, false, 8);
  const Table* head = stream.header();
  REQUIRE(head != nullptr);
  CHECK(head->names == std::vector<std::string>{"frequency", "amplitude", "stiffness", "phase"});
  CHECK(head->header_row == 2);
  CHECK_FALSE(head->rows.empty());
  CHECK(head->rows.front() == 3);
  // A fault in the lines read: no header to tell by (whole-file reading reports it).
  std::FILE* bad = std::tmpfile();
  const std::string faulty = "time [s],displacement [mm]\n0,0,1,2\n";
  std::fwrite(faulty.data(), 1, faulty.size(), bad);
  std::rewind(bad);
  HistoryStream bad_stream("b.csv", bad, false);
  CHECK(bad_stream.header() == nullptr);
}

}  // namespace history_stream_test
