// Runs the protocols of a `simulate` block on a compiled network and renders their results.
// Defaults for settings the block leaves out (documented in docs/language.md):
//   harmonic:    definition thesis, steps_per_cycle 2048, cycles_max 400, tolerance 1e-9
//   static:      cycles 2, 400 samples per cycle (dt = A / (100 v) per amplitude) unless dt is given
//   quasistatic: cycles 2, steps_per_cycle 400
//   history:     substeps 1
//   step:        dt = duration / 1000, rise = dt
//   format csv; elements none.
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

const char* protocol_name(lang::ProtocolKind kind);

}  // namespace rheo::runtime
