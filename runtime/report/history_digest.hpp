// A streamed history (protocols/stream_history.hpp) kept for a report's hysteresis loop in
// memory that does not grow with its length (#28): the samples whose index is a multiple of a
// stride, the stride a power of two doubled (and every other kept sample dropped) whenever more
// than kCapacity would be kept. So the stride ends as the least power of two s with
// ceil(n / s) <= kCapacity for n samples, and a history of at most kCapacity samples is kept
// whole: its report is the one of the history held whole (report_content.hpp). The figure
// draws at most a few thousand points of a loop (report_figures.hpp), so a longer history loses
// nothing that is drawn beyond which evenly spaced samples are.
#pragma once

#include "runtime/core/history_sink.hpp"
#include "runtime/report/report_content.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rheo::runtime::report {

class HistoryDigest : public HistorySink {
 public:
  static constexpr std::size_t kCapacity = std::size_t{1} << 16;

  HistoryDigest();
  void begin(const ResultHeader& header, const std::vector<std::string>& element_paths) override;
  void write(const History& piece) override;
  void restart() override;

  // The kept samples as a report's history (model force only), labelled LABEL.
  HistoryComparison comparison(const std::string& label) const;
  std::uint64_t samples() const { return seen_; }
  std::uint64_t stride() const { return stride_; }

 private:
  std::vector<double> displacement_, force_;  // mm, N: samples 0, stride_, 2 stride_, ...
  std::uint64_t seen_ = 0, stride_ = 1;
};

}  // namespace rheo::runtime::report
