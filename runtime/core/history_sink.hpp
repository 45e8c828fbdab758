// Where a history goes as it is made, piece by piece (protocols/stream_history.hpp), so that a
// long one need never be held whole: a result writer (io/history_writer.hpp) puts each piece in
// its file and forgets it.
#pragma once

#include "runtime/core/drive.hpp"
#include "runtime/core/protocol_result.hpp"

#include <string>
#include <vector>

namespace rheo::runtime {

class HistorySink {
 public:
  virtual ~HistorySink() = default;
  // Before the first piece: what produced the history, and the paths of the elements whose
  // force and elongation every piece carries (none without element outputs).
  virtual void begin(const ResultHeader& header, const std::vector<std::string>& element_paths) = 0;
  // The next samples, in order: PIECE's time, displacement, force and element columns, of one
  // length (its element_paths are those given to begin()).
  virtual void write(const History& piece) = 0;
  // Forgets everything since begin(): the history is made again from its start.
  virtual void restart() = 0;
};

// Hands every call to FIRST, then to SECOND (a result file and a report's digest of it).
class TeeSink : public HistorySink {
 public:
  TeeSink(HistorySink& first, HistorySink& second) : first_(first), second_(second) {}
  void begin(const ResultHeader& header, const std::vector<std::string>& element_paths) override {
    first_.begin(header, element_paths), second_.begin(header, element_paths);
  }
  void write(const History& piece) override { first_.write(piece), second_.write(piece); }
  void restart() override { first_.restart(), second_.restart(); }

 private:
  HistorySink& first_;
  HistorySink& second_;
};

}  // namespace rheo::runtime
