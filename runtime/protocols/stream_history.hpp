// A `history` protocol run as its file is read (#28): pieces of the drive from HistoryStream
// (io/history_stream.hpp), stepped by DriveStepper (stepping/drive_stepper.hpp), handed to a
// HistorySink in blocks of kBlockSamples: memory does not grow with the history's length, and
// no sample limit applies (lang/limits.hpp's max_drive_samples bounds what is held whole).
// The samples are run_protocol's (run_protocols.hpp) bit for bit: the same relaxed start at the
// first row, the same sub-samples (Drive refine) and steps, the same sample convention
// (docs/numerics.md). A fault in the file is the DataError whole-file reading gives, even where
// the file fails only after pieces were written, and it is reported before any failure of the
// simulation (the file is read to its end first); the sink must then be discarded. A file the
// stream does not take (a pipe, UTF-16, a TRIOS export: history_stream.hpp) is read whole, with
// run_protocol, and written to the sink as one piece after a restart().
#pragma once

#include "lang/model.hpp"
#include "runtime/core/history_sink.hpp"
#include "runtime/core/protocol_result.hpp"
#include "runtime/network/network.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace rheo::runtime {

inline constexpr std::size_t kBlockSamples = 4096;

// Whether PROTOCOL runs streamed: a `history` protocol, on either integrator (on IDA the file
// is read twice: first for the drive's reach and duration, which set IDA's tolerances).
bool streams(const lang::Protocol& protocol);

// How far a streamed run has come, after each piece: samples written so far and bytes of the
// file read, of FILE_BYTES.
struct StreamStatus {
  std::uint64_t samples = 0, bytes_read = 0, file_bytes = 0;
};

// What run_protocol would return besides the samples.
struct StreamedHistory {
  ResultHeader header;
  std::uint64_t samples = 0;
  std::string notes;  // warnings for standard error, one per line
};

// Runs PROTOCOL (streams() must hold) into SINK. SOURCE_FILE: the .rheo path (the history file
// is relative to its directory).
StreamedHistory stream_history(const Network& network, const lang::Protocol& protocol, const std::string& source_file, HistorySink& sink,
                               const std::function<void(const StreamStatus&)>& progress = {});

}  // namespace rheo::runtime
