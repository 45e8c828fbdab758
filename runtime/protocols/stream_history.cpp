#include "runtime/protocols/stream_history.hpp"

#include "lang/protocol_schema.hpp"
#include "runtime/io/hdf5_history.hpp"
#include "runtime/io/history_stream.hpp"
#include "runtime/protocols/run_history.hpp"
#include "runtime/protocols/run_protocols.hpp"
#include "runtime/protocols/solver_choice.hpp"
#include "runtime/dae/dae_history_stepper.hpp"
#include "runtime/stepping/drive_stepper.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
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

  // One sample, its element outputs those STEPPER holds; the block goes to SINK when full.
  template <class Stepper>
  void add(double t, double u, double force, const Stepper& stepper, HistorySink& sink) {
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

// IDA sample by sample (DaeHistoryStepper), started as run_history starts it (start_on_ida).
class IdaStepper {
 public:
  IdaStepper(const Network& network, bool elements, const DaeHistoryScales& scales) : network_(network), stepper_(network, elements, scales) {}
  double start(double t0, double u0) { return start_on_ida(network_, stepper_, t0, u0); }
  double step(double t, double u) { return stepper_.step(t, u); }
  const std::vector<double>& element_force() const { return stepper_.element_force(); }
  const std::vector<double>& element_elongation() const { return stepper_.element_elongation(); }

 private:
  const Network& network_;
  DaeHistoryStepper stepper_;
};

// Calls VISIT(t, u) for every sample of the drive STREAM hands out, its intervals cut into
// SUBSTEPS as Drive refine() cuts them (the same arithmetic: the same numbers).
template <class Stream, class Visit>
void each_sample(Stream& stream, int substeps, Visit&& visit) {
  DrivePiece piece;
  bool started = false;
  double t_before = 0.0, u_before = 0.0;  // the last row's
  while (stream.next(piece)) {
    for (std::size_t k = 0; k < piece.time.size(); ++k) {
      const double t = piece.time[k], u = piece.displacement[k];
      if (!started || substeps <= 1) {
        visit(t, u);
        started = true;
      } else {
        for (int j = 1; j <= substeps; ++j) {
          const double w = static_cast<double>(j) / substeps;
          visit(t_before + w * (t - t_before), u_before + w * (u - u_before));
        }
      }
      t_before = t, u_before = u;
    }
    visit.piece_done();
  }
}

// The streamed run proper, from STREAM (a HistoryStream or an Hdf5HistoryReader) on STEPPER
// (DriveStepper or IdaStepper); NotStreamable when the file is to be read whole.
template <class Stream, class Stepper>
StreamedHistory streamed(const Network& network, const lang::HistorySettings& s, const ResultHeader& header, Stream& stream, Stepper& stepper,
                         HistorySink& sink, const std::function<void(const StreamStatus&)>& progress) {
  Block block(network, s.elements);
  sink.begin(header, block.element_paths());
  struct Visit {
    Block& block;
    Stepper& stepper;
    HistorySink& sink;
    Stream& stream;
    const std::function<void(const StreamStatus&)>& progress;
    bool started = false;
    void operator()(double t, double u) {
      block.add(t, u, started ? stepper.step(t, u) : stepper.start(t, u), stepper, sink);
      started = true;
    }
    void piece_done() const {
      if (progress) progress({block.samples(), stream.bytes_read(), stream.file_size()});
    }
  };
  try {
    each_sample(stream, s.substeps, Visit{block, stepper, sink, stream, progress});
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

bool streams(const lang::Protocol& protocol) { return std::holds_alternative<lang::HistorySettings>(protocol.settings); }

StreamedHistory stream_history(const Network& network, const lang::Protocol& protocol, const std::string& source_file, HistorySink& sink,
                               const std::function<void(const StreamStatus&)>& progress) {
  if (!streams(protocol)) throw std::logic_error("stream_history: the protocol does not stream");
  const auto& s = std::get<lang::HistorySettings>(protocol.settings);
  const std::string file = history_file(s, source_file);
  const ResultHeader header{network.model().name, source_file, fmt::format("history file={}", file) + history_solver_note(network, s.solver)};
  const bool from_rest = s.start == lang::HistoryStart::rest;
  const bool ida = uses_sundials(network, s.solver);
  // Runs the file through a stream OPEN() makes; IDA's settings follow from the whole drive
  // (dae_history_stepper.hpp), so the file is read once for them first.
  const auto run = [&](const auto& open) {
    auto stream = open();
    if (!ida) {
      DriveStepper stepper(network, s.elements);
      return streamed(network, s, header, *stream, stepper, sink, progress);
    }
    struct Scan {
      DaeHistoryScales scales;
      void operator()(double t, double u) { scales.add(t, u); }
      void piece_done() const {}
    } scan;
    each_sample(*stream, s.substeps, scan);
    stream = open();
    IdaStepper stepper(network, s.elements, scan.scales);
    return streamed(network, s, header, *stream, stepper, sink, progress);
  };
  if (reads_as_hdf5(file))
    return run([&] { return std::make_unique<Hdf5HistoryReader>(file, &s.file_where, column_reading(s.columns), false, from_rest); });
  try {
    return run([&] {
      auto stream = std::make_unique<HistoryStream>(file, &s.file_where, from_rest);
      stream->read_columns(column_reading(s.columns));
      return stream;
    });
  } catch (const NotStreamable&) {}
  sink.restart();
  ProtocolResult whole = run_protocol(network, protocol, source_file);
  const History& h = std::get<History>(whole.data);
  sink.begin(whole.header, h.element_paths);
  sink.write(h);
  return {whole.header, h.time.size(), whole.notes};
}

}  // namespace rheo::runtime
