// A history written as CSV as it is made (core/history_sink.hpp): the text of history_csv()
// (output.hpp), byte for byte, put in a PendingOutput (output_file.hpp) kFlushBytes at a time,
// so that memory does not grow with the history.
#pragma once

#include "runtime/core/history_sink.hpp"
#include "runtime/io/output_file.hpp"

#include <string>
#include <vector>

namespace rheo::runtime {

class HistoryCsvWriter : public HistorySink {
 public:
  static constexpr std::size_t kFlushBytes = std::size_t{1} << 20;

  explicit HistoryCsvWriter(PendingOutput& out) : out_(out) {}

  void begin(const ResultHeader& header, const std::vector<std::string>& element_paths) override;
  void write(const History& piece) override;
  void restart() override;
  // Writes what is buffered; before PendingOutput::commit().
  void finish();

 private:
  PendingOutput& out_;
  std::vector<char> text_;  // kFlushBytes and room for a row
  std::size_t used_ = 0;
};

}  // namespace rheo::runtime
