#include "runtime/protocols/stream_history.hpp"

#include "lang/protocol_schema.hpp"
#include "runtime/io/hdf5_history.hpp"
#include "runtime/io/history_stream.hpp"
#include "runtime/protocols/run_protocols.hpp"
#include "runtime/protocols/solver_choice.hpp"
#include "runtime/stepping/drive_stepper.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <variant>

namespace rheo::runtime {
namespace {

// Samples collected for the sink, kBlockSamples at a time (allocated once).
class Block {
 public:
  Block(const Network& network, bool elements) {
    const std::size_t n = kBlockSamples;
    piece_.time.resize(n), piece_.displacement.resize(n), piece_.force.resize(n);
    if (!elements) return;
    for (const auto& probe : network.topology().probes) piece_.element_paths.push_back(probe.path);
    piece_.element_force.assign(piece_.element_paths.size(), std::vector<double>(n));
    piece_.element_elongation.assign(piece_.element_paths.size(), std::vector<double>(n));
  }

  const std::vector<std::string>& element_paths() const { return piece_.element_paths; }

  // One sample; the block goes to SINK when full.
  void add(double t, double u, double force, const DriveStepper& stepper, HistorySink& sink) {
    piece_.time[fill_] = t, piece_.displacement[fill_] = u, piece_.force[fill_] = force;
    for (std::size_t i = 0; i < piece_.element_paths.size(); ++i) {
      piece_.element_force[i][fill_] = stepper.element_force()[i];
      piece_.element_elongation[i][fill_] = stepper.element_elongation()[i];
    }
    reach_ = std::max(reach_, std::abs(u));
    ++samples_;
    if (++fill_ == kBlockSamples) flush(sink);
  }

  // The samples not yet handed over (the last block is cut to its length).
  void flush(HistorySink& sink) {
    if (fill_ == 0) return;
    if (fill_ < kBlockSamples) {
      for (auto* column : {&piece_.time, &piece_.displacement, &piece_.force}) column->resize(fill_);
      for (auto& column : piece_.element_force) column.resize(fill_);
      for (auto& column : piece_.element_elongation) column.resize(fill_);
    }
    sink.write(piece_);
    fill_ = 0;
  }

  std::uint64_t samples() const { return samples_; }
  double reach() const { return reach_; }

 private:
  History piece_;
  std::size_t fill_ = 0;
  std::uint64_t samples_ = 0;
  double reach_ = 0.0;  // largest |u| [mm]
};

// The streamed run proper, from STREAM (a HistoryStream or an Hdf5HistoryReader); NotStreamable
// when the file is to be read whole.
template <class Stream>
StreamedHistory streamed(const Network& network, const lang::HistorySettings& s, const ResultHeader& header, Stream& stream, HistorySink& sink,
                         const std::function<void(const StreamStatus&)>& progress) {
  DriveStepper stepper(network, s.elements);
  Block block(network, s.elements);
  sink.begin(header, block.element_paths());
  DrivePiece piece;
  bool started = false;
  double t_before = 0.0, u_before = 0.0;  // the last row's
  try {
    while (stream.next(piece)) {
      for (std::size_t k = 0; k < piece.time.size(); ++k) {
        const double t = piece.time[k], u = piece.displacement[k];
        if (!started) {
          block.add(t, u, stepper.start(t, u), stepper, sink);
          started = true;
        } else if (s.substeps <= 1) {
          block.add(t, u, stepper.step(t, u), stepper, sink);
        } else {
          for (int j = 1; j <= s.substeps; ++j) {  // as Drive refine() cuts the interval
            const double w = static_cast<double>(j) / s.substeps;
            const double tj = t_before + w * (t - t_before), uj = u_before + w * (u - u_before);
            block.add(tj, uj, stepper.step(tj, uj), stepper, sink);
          }
        }
        t_before = t, u_before = u;
      }
      if (progress) progress({block.samples(), stream.bytes_read(), stream.file_size()});
    }
    block.flush(sink);
  } catch (const NotStreamable&) {
    throw;
  } catch (...) {
    stream.drain();  // a fault in the file first, as whole-file reading reports it
    throw;
  }
  return {header, block.samples(), yeoh_softening_note(network, block.reach())};
}

}  // namespace

bool streams(const Network& network, const lang::Protocol& protocol) {
  const auto* s = std::get_if<lang::HistorySettings>(&protocol.settings);
  return s && !uses_sundials(network, s->solver);
}

StreamedHistory stream_history(const Network& network, const lang::Protocol& protocol, const std::string& source_file, HistorySink& sink,
                               const std::function<void(const StreamStatus&)>& progress) {
  if (!streams(network, protocol)) throw std::logic_error("stream_history: the protocol does not stream");
  const auto& s = std::get<lang::HistorySettings>(protocol.settings);
  const std::string file = history_file(s, source_file);
  const ResultHeader header{network.model().name, source_file, fmt::format("history file={}", file)};
  const bool from_rest = s.start == lang::HistoryStart::rest;
  if (reads_as_hdf5(file)) {
    Hdf5HistoryReader stream(file, &s.file_where, column_reading(s.columns), false, from_rest);
    return streamed(network, s, header, stream, sink, progress);
  }
  try {
    HistoryStream stream(file, &s.file_where, from_rest);
    stream.read_columns(column_reading(s.columns));
    return streamed(network, s, header, stream, sink, progress);
  } catch (const NotStreamable&) {}
  sink.restart();
  ProtocolResult whole = run_protocol(network, protocol, source_file);
  const History& h = std::get<History>(whole.data);
  sink.begin(whole.header, h.element_paths);
  sink.write(h);
  return {whole.header, h.time.size(), whole.notes};
}

}  // namespace rheo::runtime
