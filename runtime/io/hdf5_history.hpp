// A history read from an HDF5 file (docs/data-formats.md, "HDF5 files"): time, displacement and,
// for a measured history, force, each a dataset of numbers (any floating-point or integer type,
// read as doubles), of rank 1 or an N x 1 or 1 x N matrix (as MATLAB's v7.3 .mat files hold a
// vector), read in pieces of at most kPieceSamples (hyperslabs): memory does not grow with the
// history's length.
//
// Which datasets (found by hdf5_layout.hpp): those the reading names for a role (`columns = "time = /rig/t"`: a path, from
// the root when it does not start with '/'), else the first dataset of the root group whose name
// is one of the role's usual names (column_roles.hpp) and whose unit suits it: rheo's own result
// (/time, /displacement, /force) reads back. The unit of each: written after the path on the
// data line (`/rig/t [ms]`), else the dataset's "units" attribute (a string); one of neither is
// an error, as a CSV column without a unit is.
//
// A MATLAB v7.3 .mat file is read so (matlab_file.hpp): its variables are datasets, a struct's
// fields datasets in its group (`columns = "time = rig.t"` for /rig/t), and those that are not
// real numbers (text, logical, cell, complex, ...) are refused naming the variable.
//
// Faults are DataErrors naming the file, the dataset and, for values, the 0-based index, with
// what to do: a file that is not HDF5, a dataset that is missing (naming what the group holds),
// a group where a dataset is expected, a rank or type rheo cannot read, datasets of different
// lengths, fewer than two samples, a unit missing, unknown or of another kind, a value that is
// not a finite number, time not increasing, a displacement no rig drives, start = rest not met
// (found at the end). The first in index order is thrown; a caller keeps its results
// provisional until next() has returned false, as with HistoryStream (history_stream.hpp).
#pragma once

#include "lang/source_location.hpp"
#include "runtime/io/column_roles.hpp"
#include "runtime/io/fit_data.hpp"
#include "runtime/io/hdf5_layout.hpp"
#include "runtime/io/hdf5_owners.hpp"
#include "runtime/io/history_stream.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace rheo::runtime {

// Whether PATH names an HDF5 file: it ends in .h5 or .hdf5 (any case).
bool is_hdf5_name(const std::string& path);
// Whether a history or measured data at PATH is read as HDF5: an HDF5 name, or a MATLAB .mat
// file (v7.3 is HDF5; matlab_file.hpp).
bool reads_as_hdf5(const std::string& path);

class Hdf5HistoryReader {
 public:
  static constexpr std::size_t kPieceSamples = 65536;

  // Opens PATH (NAMED_AT: where a .rheo file names it, for a file that cannot be read) and checks
  // its datasets' shapes, types, lengths and units. FORCE: read a measured force too.
  // FROM_REST: start = rest.
  Hdf5HistoryReader(std::string path, const lang::SourceLocation* named_at, const ColumnReading& reading, bool force, bool from_rest,
                    std::size_t piece_samples = kPieceSamples);
  ~Hdf5HistoryReader();
  Hdf5HistoryReader(const Hdf5HistoryReader&) = delete;
  Hdf5HistoryReader& operator=(const Hdf5HistoryReader&) = delete;

  // The next samples into PIECE (time from the first sample's, in s; displacement in mm; rows:
  // 0-based indices) and, when reading force, FORCE (N): true; false at the end of a history that
  // passed every check. DataError at a fault.
  bool next(DrivePiece& piece, std::vector<double>* force = nullptr);
  // Reads the rest and throws the first fault, if any (as HistoryStream::drain).
  void drain();

  std::uint64_t samples() const { return samples_; }
  // For progress: bytes of the file read so far (in proportion to the samples), and its size.
  std::uint64_t bytes_read() const;
  std::uint64_t file_size() const { return file_bytes_; }

 private:
  void read(Hdf5Column& column, std::uint64_t start, std::size_t count, std::vector<double>& out);
  [[noreturn]] void value_fault(const Hdf5Column& column, std::uint64_t index, const std::string& what, const std::string& advice);

  std::string path_;
  bool from_rest_;
  std::size_t piece_samples_;
  hdf5::File file_;
  std::vector<Hdf5Column> columns_;  // time, displacement[, force]
  std::uint64_t samples_ = 0, next_ = 0, file_bytes_ = 0;
  double t0_ = 0.0, u0_ = 0.0, last_t_ = 0.0, largest_ = 0.0;
  bool force_seen_ = false;  // a nonzero force
  std::string fault_;        // the fault thrown, thrown again by every later next()
  std::vector<double> buffer_;
};

// The drive of a `history` protocol's HDF5 file, whole (for the integrators that hold it:
// SUNDIALS, JSON output), checked as the reader checks it; at most lang::max_drive_samples
// samples (a DataError before anything is read beyond that).
Drive read_hdf5_drive(const std::string& path, const lang::SourceLocation* named_at, const ColumnReading& reading, bool from_rest);
// A measured history (time, displacement, force) for fits and reports, held as doubles (each
// sample's index its row), kHeldSampleBytes a sample, within lang::max_table_bytes (the bound of a
// table held whole; a DataError before anything is read beyond it).
HistoryData read_hdf5_history(const std::string& path, const lang::SourceLocation* named_at, const ColumnReading& reading);

}  // namespace rheo::runtime
