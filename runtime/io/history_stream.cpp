#include "runtime/io/history_stream.hpp"

#include "lang/file_text.hpp"
#include "lang/text_encoding.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/io/column_roles.hpp"
#include "runtime/io/drive_faults.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

namespace rheo::runtime {
namespace {

std::string failure_message(const std::string& path, const lang::SourceLocation* named_at, const std::string& failure) {
  lang::FileText text;
  text.failure = failure;
  return unreadable_table(path, named_at, failure, text.advice());
}

}  // namespace

HistoryStream::HistoryStream(std::string path, const lang::SourceLocation* named_at, bool from_rest, std::size_t block_bytes)
    : path_(std::move(path)), named_at_(named_at), from_rest_(from_rest) {
  table_.path = path_;
  std::error_code error;
  if (std::filesystem::is_directory(path_, error)) throw DataError(failure_message(path_, named_at_, "it is a directory"));
  file_ = std::fopen(path_.c_str(), "rb");
  if (!file_) throw DataError(failure_message(path_, named_at_, std::strerror(errno)));
  take_regular_file(block_bytes);
}

void HistoryStream::take_regular_file(std::size_t block_bytes) {
  struct stat status {};
  if (::fstat(::fileno(file_), &status) != 0 || !S_ISREG(status.st_mode)) {
    std::fclose(file_);
    file_ = nullptr;
    throw NotStreamable("not a regular file");
  }
  size_ = static_cast<std::uint64_t>(status.st_size);
  buffer_.resize(std::max(block_bytes, kSignatureBytes));
}

HistoryStream::HistoryStream(std::string path, std::FILE* file, bool from_rest, std::size_t block_bytes)
    : path_(std::move(path)), named_at_(nullptr), from_rest_(from_rest), file_(file) {
  table_.path = path_;
  take_regular_file(block_bytes);
}

HistoryStream::~HistoryStream() {
  if (file_) std::fclose(file_);
}

bool HistoryStream::read_block() {
  if (at_end_) return false;
  // Keep the unfinished line, at the front; a line that fills the buffer grows it.
  std::copy(buffer_.begin() + static_cast<std::ptrdiff_t>(begin_), buffer_.begin() + static_cast<std::ptrdiff_t>(end_), buffer_.begin());
  end_ -= begin_;
  begin_ = 0;
  if (end_ == buffer_.size()) {
    if (buffer_.size() >= kMaxLineBytes) throw NotStreamable(fmt::format("a line longer than {} MiB", kMaxLineBytes >> 20));
    buffer_.resize(std::min(2 * buffer_.size(), kMaxLineBytes));
  }
  const std::size_t got = std::fread(buffer_.data() + end_, 1, buffer_.size() - end_, file_);
  if (std::ferror(file_)) throw DataError(failure_message(path_, named_at_, std::strerror(errno)));
  read_ += got;
  end_ += got;
  if (!started_) {
    started_ = true;
    const std::string_view start(buffer_.data(), std::min(end_, kSignatureBytes));
    refuse_workbook(path_, start);
    if (is_utf16(start)) throw NotStreamable("UTF-16 text");
    if (start.starts_with("\xEF\xBB\xBF")) begin_ = 3;
  }
  if (got == 0) at_end_ = true;
  return got > 0;
}

bool HistoryStream::take_lines() {
  if (!read_block()) {
    if (begin_ < end_) take_line(std::string_view(buffer_.data() + begin_, end_ - begin_));  // the last line, without '\n'
    begin_ = end_;
    return false;
  }
  while (const void* newline = std::memchr(buffer_.data() + begin_, '\n', end_ - begin_)) {
    const auto at = static_cast<std::size_t>(static_cast<const char*>(newline) - buffer_.data());
    take_line(std::string_view(buffer_.data() + begin_, at - begin_));
    begin_ = at + 1;
  }
  return true;
}

void HistoryStream::take_line(std::string_view line) {
  if (row_ == std::numeric_limits<int>::max())
    throw DataError(fmt::format("{}:{}:1: error: the file has more lines than rheo counts ({}); split it", path_, row_, row_));
  ++row_;
  if (encoding_fault_.empty())
    if (const auto problem = lang::find_encoding_problem(line)) {
      encoding_fault_ = fmt::format("{}:{}:{}: error: {}", path_, row_, problem->offset + 1, problem->description);
      faulty_ = true;
    }
  if (is_step_line(line)) throw NotStreamable("a TRIOS export");
  if (!layout_found_) {
    if (TableRows::skips(line)) return;
    if (!holds_layout(line)) throw NotStreamable("a names row the layout is not read from");
    layout_ = plain_layout(line);
    layout_found_ = true;
  }
  if (!width_fault_.empty()) return;  // whole-file reading stops at that row
  try {
    rows_.line(line, row_);
  } catch (const DataError& e) {
    width_fault_ = e.what();
    faulty_ = true;
  }
}

const Table* HistoryStream::header() {
  while (table_.rows.empty() && !faulty_ && take_lines()) {}
  return faulty_ ? nullptr : &table_;
}

void HistoryStream::check_force_column() {
  try {
    f_ = find_role(table_, Role::force, reading_);
    if (f_ < 0) throw DataError(drive_faults::missing_force(table_));
    (void)role_values(table_, f_, Role::force, reading_);
  } catch (const DataError&) {
    faulty_ = true;
  }
}

void HistoryStream::check_rows(DrivePiece* piece, std::vector<double>* force) {
  const std::size_t n = table_.rows.size();
  if (n == 0) return;
  if (!columns_checked_) {
    columns_checked_ = true;
    try {
      t_ = find_role(table_, Role::time, reading_);  // a column reading_ names that the header lacks: DataError
      u_ = find_role(table_, Role::displacement, reading_);
      if (t_ < 0 || u_ < 0) throw DataError(drive_faults::missing_columns(table_));
      (void)role_values(table_, t_, Role::time, reading_);  // its units (and cells)
      (void)role_values(table_, u_, Role::displacement, reading_);
    } catch (const DataError&) {
      faulty_ = true;
    }
    if (force_) check_force_column();
  }
  if (t_ >= 0 && u_ >= 0) {
    const auto t = static_cast<std::size_t>(t_), u = static_cast<std::size_t>(u_);
    if (!table_.problems[t].empty() || !table_.problems[u].empty()) faulty_ = true;
    const std::vector<double>& time = table_.columns[t];
    const std::vector<double>& disp = table_.columns[u];
    const std::vector<double>* forces = f_ >= 0 ? &table_.columns[static_cast<std::size_t>(f_)] : nullptr;
    if (forces && !table_.problems[static_cast<std::size_t>(f_)].empty()) faulty_ = true;
    for (std::size_t i = 0; i < n; ++i) {
      const int row = table_.rows[i];
      if (data_rows_ == 0) {
        t0_ = time[i], u0_ = disp[i], first_row_ = row;
        first_u_column_ = table_.cell_column(i, u_);
        if (forces) first_f_column_ = table_.cell_column(i, f_);
      } else if (!(time[i] > last_t_) && row_fault_.empty()) {
        row_fault_ = drive_faults::time_not_increasing(path_, row, table_.cell_column(i, t_), time[i], last_t_, last_row_);
        faulty_ = true;
      }
      if (!drive_faults::drivable(disp[i]) && row_fault_.empty()) {
        row_fault_ = drive_faults::not_drivable(path_, row, table_.cell_column(i, u_), disp[i]);
        faulty_ = true;
      }
      largest_ = std::max(largest_, std::abs(disp[i]));
      last_t_ = time[i], last_row_ = row;
      if (forces) force_seen_ = force_seen_ || (*forces)[i] != 0.0;
      ++data_rows_;
      if (piece && !faulty_) {
        piece->time.push_back(time[i] - t0_);
        piece->displacement.push_back(disp[i]);
        piece->rows.push_back(row);
        if (force && forces) force->push_back((*forces)[i]);
      }
    }
  } else {
    if (data_rows_ == 0) first_row_ = table_.rows[0];
    data_rows_ += n;
  }
  for (auto& column : table_.columns) column.clear();
  table_.rows.clear();
  table_.cell_columns.clear();
}

void HistoryStream::settle() {
  if (!encoding_fault_.empty()) throw DataError(encoding_fault_);
  if (!width_fault_.empty()) throw DataError(width_fault_);
  rows_.finish(data_rows_);
  const int f = force_ ? find_role(table_, Role::force, reading_) : -1;  // as history_data_from_table: before the drive
  if (force_ && f < 0) throw DataError(drive_faults::missing_force(table_));
  const int t = find_role(table_, Role::time, reading_), u = find_role(table_, Role::displacement, reading_);
  if (t < 0 || u < 0) throw DataError(drive_faults::missing_columns(table_));
  (void)role_values(table_, t, Role::time, reading_);
  (void)role_values(table_, u, Role::displacement, reading_);
  if (data_rows_ < 2) throw DataError(drive_faults::too_few_rows(path_, first_row_));
  if (from_rest_ && !drive_faults::starts_at_rest(u0_, largest_))
    throw DataError(drive_faults::not_at_rest(path_, first_row_, first_u_column_, u0_));
  if (!row_fault_.empty()) throw DataError(row_fault_);
  if (force_) {
    (void)role_values(table_, f, Role::force, reading_);
    if (!force_seen_) throw DataError(drive_faults::zero_force(path_, first_row_, first_f_column_));
  }
}

void HistoryStream::drain() {
  while (take_lines()) check_rows(nullptr, nullptr);
  check_rows(nullptr, nullptr);
  settle();
}

void HistoryStream::fail_at_first_fault() {
  drain();
  throw std::logic_error("HistoryStream: a fault was found that settle() does not report");
}

bool HistoryStream::next(DrivePiece& piece, std::vector<double>* force) {
  piece.clear();
  if (force) force->clear();
  while (!faulty_) {
    const bool more = take_lines();
    check_rows(&piece, force);
    if (faulty_) break;
    if (!more) {
      settle();
      return !piece.time.empty();
    }
    if (!piece.time.empty()) return true;
  }
  fail_at_first_fault();
}

}  // namespace rheo::runtime
