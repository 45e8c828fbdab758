#include "runtime/io/hdf5_history.hpp"

#include "lang/limits.hpp"
#include "lang/text_encoding.hpp"
#include "runtime/io/drive_faults.hpp"
#include "runtime/io/matlab_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>

namespace rheo::runtime {
namespace {

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return text;
}

}  // namespace

bool is_hdf5_name(const std::string& path) {
  const std::string name = lower(path);
  return name.ends_with(".h5") || name.ends_with(".hdf5");
}

bool reads_as_hdf5(const std::string& path) { return is_hdf5_name(path) || is_matlab_name(path); }


Hdf5HistoryReader::Hdf5HistoryReader(std::string path, const lang::SourceLocation* named_at, const ColumnReading& reading, bool force,
                                     bool from_rest, std::size_t piece_samples)
    : path_(std::move(path)), from_rest_(from_rest), piece_samples_(std::max<std::size_t>(piece_samples, 1)) {
  hdf5::library();
  const std::string& file = path_;
  const std::string shown = lang::printable(file);
  {
    std::error_code error;
    if (std::filesystem::is_directory(file, error)) throw DataError(unreadable_table(file, named_at, "it is a directory", "name a file"));
    std::FILE* probe = std::fopen(file.c_str(), "rb");
    if (!probe) throw DataError(unreadable_table(file, named_at, std::strerror(errno), "check the name and that the file is readable"));
    std::fclose(probe);
  }
  const htri_t is_hdf5 = H5Fis_hdf5(file.c_str());
  if (is_hdf5 <= 0) {
    hdf5::last_error();
    if (is_matlab_name(file)) refuse_non_hdf5_matlab(file);
    throw DataError(
        fmt::format("{}: error: this is not an HDF5 file (rheo reads a file named .h5 or .hdf5 as HDF5); give the HDF5 file, "
                    "or name a CSV table .csv",
                    shown));
  }
  file_ = hdf5::File(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), file, "H5Fopen", "the file");
  hsize_t bytes = 0;
  hdf5::check(H5Fget_filesize(file_.get(), &bytes), file, "H5Fget_filesize", "the file");
  file_bytes_ = bytes;

  std::vector<Role> roles{Role::time, Role::displacement};
  if (force) roles.push_back(Role::force);
  columns_ = hdf5_columns(file_.get(), file, roles, reading);

  const Hdf5Column& time = columns_.front();
  for (const auto& column : columns_)
    if (column.length != time.length)
      throw DataError(fmt::format("{}: error: the datasets differ in length: {} has {} samples, {} has {}; a history needs a {} at every time", shown,
                                  lang::printable(time.path), time.length, lang::printable(column.path), column.length, role_name(column.role)));
  if (time.length < 2)
    throw DataError(fmt::format("{}: error: {} has {} sample{}; a history needs at least two", shown, lang::printable(time.path), time.length,
                                time.length == 1 ? "" : "s"));
  samples_ = time.length;
  buffer_.reserve(piece_samples_);
}

Hdf5HistoryReader::~Hdf5HistoryReader() = default;

std::uint64_t Hdf5HistoryReader::bytes_read() const {
  return samples_ == 0 ? 0
                       : static_cast<std::uint64_t>(static_cast<double>(file_bytes_) * static_cast<double>(next_) / static_cast<double>(samples_));
}

void Hdf5HistoryReader::read(Hdf5Column& column, std::uint64_t start, std::size_t count, std::vector<double>& out) {
  out.resize(count);
  hsize_t offset[2] = {0, 0}, extent[2] = {1, 1};
  offset[column.axis] = start;
  extent[column.axis] = count;
  hdf5::check(H5Sselect_hyperslab(column.space.get(), H5S_SELECT_SET, offset, nullptr, extent, nullptr), path_, "H5Sselect_hyperslab", column.path);
  const hsize_t n = count;
  hdf5::Dataspace memory(H5Screate_simple(1, &n, nullptr), path_, "H5Screate_simple", column.path);
  hdf5::check(H5Dread(column.dataset.get(), H5T_NATIVE_DOUBLE, memory.get(), column.space.get(), H5P_DEFAULT, out.data()), path_, "H5Dread",
              column.path);
  if (column.scale != 1.0)
    for (double& v : out) v *= column.scale;
}

void Hdf5HistoryReader::value_fault(const Hdf5Column& column, std::uint64_t index, const std::string& what, const std::string& advice) {
  fault_ = fmt::format("{}: error: {}[{}] ({}) {}; {}", lang::printable(path_), lang::printable(column.path), index, role_name(column.role), what,
                       advice);
  throw DataError(fault_);
}

bool Hdf5HistoryReader::next(DrivePiece& piece, std::vector<double>* force) {
  piece.clear();
  if (force) force->clear();
  if (!fault_.empty()) throw DataError(fault_);  // found before: drain() after a failed next() reports it again
  if (next_ == samples_) {
    if (from_rest_ && !drive_faults::starts_at_rest(u0_, largest_))
      value_fault(columns_[1], 0, fmt::format("is {:g} mm", u0_),
                  "start = rest needs displacement 0 at the first sample; remove start = rest to start relaxed there, or shift the "
                  "displacement");
    if (columns_.size() > 2 && !force_seen_) {
      fault_ = fmt::format("{}: error: every force in {} is zero; a fit needs a force signal: check the dataset and its unit",
                           lang::printable(path_), lang::printable(columns_[2].path));
      throw DataError(fault_);
    }
    return false;
  }
  const std::uint64_t first = next_;
  const auto count = static_cast<std::size_t>(std::min<std::uint64_t>(piece_samples_, samples_ - first));
  read(columns_[0], first, count, piece.time);
  read(columns_[1], first, count, piece.displacement);
  if (force) read(columns_[2], first, count, *force);
  else if (columns_.size() > 2) read(columns_[2], first, count, buffer_);
  const std::vector<double>* forces = force ? force : columns_.size() > 2 ? &buffer_ : nullptr;
  piece.rows.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint64_t i = first + k;
    const double t = piece.time[k], u = piece.displacement[k];
    if (!std::isfinite(t))
      value_fault(columns_[0], i, fmt::format("is {}", t), "every time must be a finite number: remove the sample or mend the recording");
    if (!std::isfinite(u))
      value_fault(columns_[1], i, fmt::format("is {}", u), "every displacement must be a finite number: remove the sample or mend the recording");
    if (forces) {
      const double f = (*forces)[k];
      if (!std::isfinite(f))
        value_fault(columns_[2], i, fmt::format("is {}", f), "every force must be a finite number: remove the sample or mend the recording");
      force_seen_ = force_seen_ || f != 0.0;
    }
    if (i == 0) {
      t0_ = t, u0_ = u;
    } else if (!(t > last_t_)) {
      value_fault(columns_[0], i, fmt::format("= {:g} s is not after [{}] = {:g} s", t, i - 1, last_t_),
                  "time must increase from sample to sample: remove repeated samples or sort the history by time");
    }
    if (!drive_faults::drivable(u))
      value_fault(columns_[1], i, fmt::format("= {:g} mm is beyond the {:g} mm a rig can drive", u, lang::max_amplitude), "check the dataset's unit");
    largest_ = std::max(largest_, std::abs(u));
    last_t_ = t;
    piece.time[k] = t - t0_;
    piece.rows[k] = static_cast<int>(std::min<std::uint64_t>(i, static_cast<std::uint64_t>(std::numeric_limits<int>::max())));
  }
  next_ += count;
  return true;
}

void Hdf5HistoryReader::drain() {
  DrivePiece piece;
  while (next(piece)) {}
}

Drive read_hdf5_drive(const std::string& path, const lang::SourceLocation* named_at, const ColumnReading& reading, bool from_rest) {
  Hdf5HistoryReader reader(path, named_at, reading, false, from_rest);
  if (reader.samples() > static_cast<std::uint64_t>(lang::max_drive_samples))
    throw DataError(
        fmt::format("{}: error: the history has {} samples, more than the {} rheo holds whole (SUNDIALS, JSON output); write it as "
                    "CSV or HDF5 on the fixed-step solver, which streams it, or split the file",
                    lang::printable(path), reader.samples(), lang::max_drive_samples));
  Drive drive;
  drive.time.reserve(reader.samples()), drive.displacement.reserve(reader.samples());
  DrivePiece piece;
  while (reader.next(piece)) {
    drive.time.insert(drive.time.end(), piece.time.begin(), piece.time.end());
    drive.displacement.insert(drive.displacement.end(), piece.displacement.begin(), piece.displacement.end());
  }
  return drive;
}

HistoryData read_hdf5_history(const std::string& path, const lang::SourceLocation* named_at, const ColumnReading& reading) {
  Hdf5HistoryReader reader(path, named_at, reading, true, false);
  const std::uint64_t most = lang::max_table_bytes / kHeldSampleBytes;
  if (reader.samples() > most)
    throw DataError(
        fmt::format("{}: error: the history has {} samples, more than the {} a fit or report holds ({} MiB at {} bytes a sample); "
                    "fit a part of it, or resample it",
                    lang::printable(path), reader.samples(), most, lang::max_table_bytes >> 20, kHeldSampleBytes));
  HistoryData h;
  h.path = path;
  const auto n = static_cast<std::size_t>(reader.samples());
  h.drive.time.reserve(n), h.drive.displacement.reserve(n), h.force.reserve(n);
  DrivePiece piece;
  std::vector<double> force;
  while (reader.next(piece, &force)) h.append(piece, force);
  h.set_force_scale();
  return h;
}

}  // namespace rheo::runtime
