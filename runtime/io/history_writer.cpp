#include "runtime/io/history_writer.hpp"

#include "runtime/io/output.hpp"

#include <string_view>

namespace rheo::runtime {

void HistoryCsvWriter::begin(const ResultHeader& header, const std::vector<std::string>& element_paths) {
  out_.write(history_csv_head(header, element_paths));
  text_.resize(kFlushBytes + max_history_row_bytes(element_paths.size()));
  used_ = 0;
}

void HistoryCsvWriter::write(const History& piece) {
  char* const start = text_.data();
  char* p = start + used_;
  for (std::size_t k = 0; k < piece.time.size(); ++k) {
    p = write_history_row(p, piece, k);
    if (static_cast<std::size_t>(p - start) >= kFlushBytes) {
      out_.write(std::string_view(start, static_cast<std::size_t>(p - start)));
      p = start;
    }
  }
  used_ = static_cast<std::size_t>(p - start);
}

void HistoryCsvWriter::restart() {
  used_ = 0;
  out_.restart();
}

void HistoryCsvWriter::finish() {
  out_.write(std::string_view(text_.data(), used_));
  used_ = 0;
}

}  // namespace rheo::runtime
