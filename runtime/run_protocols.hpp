// Runs the protocols of a `simulate` block on a compiled network and renders their results.
// The protocol's typed settings carry the defaults of what the block leaves out
// (lang/protocol_settings.hpp, docs/language.md).
#pragma once

#include "lang/model.hpp"
#include "runtime/network.hpp"

#include <string>

namespace rheo::runtime {

struct ProtocolRun {
  std::string content;      // the rendered result (CSV or JSON)
  int points = 0;           // harmonic points or history samples
  int not_converged = 0;    // harmonic points that did not reach steady state
  std::string notes;        // warnings for standard error, one per line
};

// `source_file` is the .rheo path (history files are relative to its directory).
// `threads`: harmonic grid points simulated at once (HarmonicOptions::threads).
ProtocolRun run_protocol(const Network& network, const lang::Protocol& protocol, const std::string& source_file,
                         int threads = 1);

}  // namespace rheo::runtime
