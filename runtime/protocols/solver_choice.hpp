// Which integrator steps a network: `fixed` the fixed-step kernels (simulator.hpp), `sundials`
// the variable-step IDA backend (dae_integrator.hpp), `automatic` IDA for networks with an
// inerter (where fixed steps are only second order and the resonance of an internal mass
// needs many steps per cycle) or with series and parallel blocks alternating more than
// kFixedStepMaxBlockDepth deep (the fixed-step tree solver nests one Newton solve per level,
// so its cost grows geometrically with the depth: ~0.15 s per harmonic point at 3, ~10 s at 4),
// and the fixed-step kernels otherwise (exact for networks whose elements all sit in the root
// parallel block, first order in nested dashpots). A network with a bouc_wen inside a series
// block (between internal nodes) takes fixed steps whatever its inerters and depth: they
// integrate the law over each step's elongation increment, within 1.3e-2 of max |F| at one step
// a sample on differential seed 37, model 85, and far faster than IDA there (0.01 s against
// 3.4 s for a 1 s history, docs/numerics.md). IDA, which failed there until the law's
// loading switch became an event (dae_bouc_wen.cpp), is the accurate choice (2.4e-7).
#pragma once

#include "lang/protocol_settings.hpp"
#include "runtime/network/network.hpp"

#include <optional>
#include <string_view>

namespace rheo::runtime {

using lang::SolverChoice;  // the `solver` setting's vocabulary (lang/protocol_settings.hpp)

inline constexpr int kFixedStepMaxBlockDepth = 3;  // nested blocks below the model's body

// Whether `choice` resolves to the SUNDIALS backend for this network.
bool uses_sundials(const Network& network, SolverChoice choice);

// Whether the network holds an inerter anywhere.
bool has_inerter(const Network& network);

}  // namespace rheo::runtime
