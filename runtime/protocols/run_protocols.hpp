// Runs the protocols of a `simulate` block on a compiled network and hands back their results
// as data (protocol_result.hpp). The protocol's typed settings carry the defaults of what the
// block leaves out (lang/protocol_settings.hpp, docs/language.md); their `format` is for the
// caller that renders the result (output.hpp).
#pragma once

#include "lang/model.hpp"
#include "runtime/network/network.hpp"
#include "runtime/core/protocol_result.hpp"

#include <string>

namespace rheo::runtime {

// `source_file` is the .rheo path (history files are relative to its directory).
// `threads`: harmonic grid points simulated at once (HarmonicOptions::threads).
ProtocolResult run_protocol(const Network& network, const lang::Protocol& protocol, const std::string& source_file, int threads = 1);

// The parts of a history's result stream_history.hpp shares: the file a `history` protocol
// reads, and the warnings for a drive reaching REACH [mm] (a root yeoh softening before it).
std::string history_file(const lang::HistorySettings& settings, const std::string& source_file);
std::string yeoh_softening_note(const Network& network, double reach);
// What a history's header adds to its protocol's description where IDA runs it: " solver=sundials
// (IDA, rtol 1e-08)"; empty on the fixed-step kernels.
std::string history_solver_note(const Network& network, lang::SolverChoice solver);

}  // namespace rheo::runtime
