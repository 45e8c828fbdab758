// A displacement history read from a CSV file piece by piece, in memory that does not grow with
// the file (a block of kBlockBytes at a time; a longer line grows it, to kMaxLineBytes), for
// `history` protocols whatever their length (docs/data-formats.md, "Long histories").
//
// It reads as drive_from_table(read_table(PATH)) reads (history_csv.hpp) and checks all it
// checks, with the same rows of code (table_rows.hpp, drive_faults.hpp). A faulty file fails
// with the DataError whole-file reading would give, at the same file:row:column, wherever in
// the file the fault sits: once a fault is found no further piece is handed out, the rest of
// the file is read, and of the faults found the one whole-file reading reports first is thrown
// (an encoding fault, then a row with too many values, no header or no data rows, a missing
// column, a bad cell or unit of time, then of displacement, fewer than two rows, start = rest
// not met, then time not increasing or a displacement no rig drives, in row order). So a piece
// handed out may precede a fault further down: a caller keeps its results provisional until
// next() has returned false.
//
// A measured history (fit_data.hpp) is read so too, with its force (read_force()): the force
// column's faults (its unit, its cells) follow the drive's, then a force zero everywhere, as
// history_data_from_table reports them.
//
// Files it does not take throw NotStreamable, before or while pieces are handed out, for the
// caller to read whole (with its bound on size): what is not a regular file (a pipe, a device:
// it may never end, and a fault makes the stream read to the end), UTF-16 text, TRIOS exports
// (a "[step]" line anywhere), a names row that is not where the layout is read from (a line of
// CRs and blanks), a line longer than kMaxLineBytes.
#pragma once

#include "lang/source_location.hpp"
#include "runtime/io/column_roles.hpp"
#include "runtime/io/history_csv.hpp"
#include "runtime/io/table_layout.hpp"
#include "runtime/io/table_rows.hpp"

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace rheo::runtime {

struct NotStreamable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Consecutive samples of the drive.
struct DrivePiece {
  std::vector<double> time;          // s, from the first row's time (the drive starts at 0)
  std::vector<double> displacement;  // mm
  std::vector<int> rows;             // 1-based file line of each sample
  void clear() { time.clear(), displacement.clear(), rows.clear(); }
};

class HistoryStream {
 public:
  static constexpr std::size_t kBlockBytes = std::size_t{1} << 20;
  static constexpr std::size_t kMaxLineBytes = std::size_t{64} << 20;

  // Opens PATH (NAMED_AT: where a .rheo file names it, for a file that cannot be read, as
  // read_table). FROM_REST: start = rest. BLOCK_BYTES: bytes read at a time (tests make it small).
  HistoryStream(std::string path, const lang::SourceLocation* named_at, bool from_rest, std::size_t block_bytes = kBlockBytes);
  // Reads FILE, open for reading (taken over: closed here), as the file PATH (the fuzz target
  // reads from memory, with fmemopen).
  HistoryStream(std::string path, std::FILE* file, bool from_rest, std::size_t block_bytes = kBlockBytes);
  ~HistoryStream();
  HistoryStream(const HistoryStream&) = delete;
  HistoryStream& operator=(const HistoryStream&) = delete;

  // The columns a history protocol's `columns` names (column_roles.hpp); before the first next().
  void read_columns(ColumnReading reading) { reading_ = std::move(reading); }
  // Reads the force too (a measured history), handed out by next(piece, force); before the
  // first next().
  void read_force() { force_ = true; }

  // The names row and units of the file, and its first data rows, read (as far as the first data
  // row, or the end of a file without one) for a caller to tell the kind of table before taking
  // pieces; nullptr when a fault in the lines read stops the table there (whole-file reading
  // reports it). NotStreamable as next().
  const Table* header();

  // The next samples into PIECE (replacing what it held; at least one): true; false at the end
  // of a file that passed every check. DataError at a fault (see above), NotStreamable.
  bool next(DrivePiece& piece, std::vector<double>* force = nullptr);
  // For a caller whose own work failed: reads the rest of the file and throws the DataError it
  // holds (or NotStreamable), so that a fault in the data is reported before the failure it
  // caused, as when the file is read whole; returns when the file is sound.
  void drain();

  // Bytes read so far and the file's size, for progress.
  std::uint64_t bytes_read() const { return read_; }
  std::uint64_t file_size() const { return size_; }

 private:
  void take_regular_file(std::size_t block_bytes);  // NotStreamable for a pipe or a device
  bool read_block();                                // more bytes into the buffer; false at the end of the file
  bool take_lines();                                // every whole line in the buffer; false at the end of the file
  void take_line(std::string_view line);
  void check_rows(DrivePiece* piece, std::vector<double>* force);  // the data rows read since the last call
  void check_force_column();
  [[noreturn]] void fail_at_first_fault();
  void settle();  // at the end of the file: throws the first fault, if any

  std::string path_;
  const lang::SourceLocation* named_at_;
  bool from_rest_;
  std::FILE* file_ = nullptr;
  std::uint64_t size_ = 0, read_ = 0;
  std::vector<char> buffer_;
  std::size_t begin_ = 0, end_ = 0;  // unread bytes of buffer_
  bool at_end_ = false, started_ = false;
  int row_ = 0;  // file line of the last line taken

  Table table_;  // names, units and problems of the whole file; the data rows since check_rows
  TableLayout layout_;
  bool layout_found_ = false;
  TableRows rows_{table_, layout_};

  ColumnReading reading_;
  int t_ = -1, u_ = -1;  // the time and displacement columns, once a data row is read
  bool columns_checked_ = false;
  std::size_t data_rows_ = 0;
  int first_row_ = 0, first_u_column_ = 1;
  double t0_ = 0.0, u0_ = 0.0, last_t_ = 0.0, largest_ = 0.0;
  int last_row_ = 0;
  bool force_ = false;
  int f_ = -1;               // the force column, when reading force
  int first_f_column_ = 1;   // the first row's force cell
  bool force_seen_ = false;  // a force that is not zero

  bool faulty_ = false;                                   // a fault is known: no more pieces
  std::string encoding_fault_, width_fault_, row_fault_;  // the first of each kind
};

}  // namespace rheo::runtime
