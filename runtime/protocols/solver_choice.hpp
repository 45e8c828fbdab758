// Which integrator steps a network: `fixed` the fixed-step kernels (simulator.hpp), `sundials`
// the variable-step IDA backend (dae_integrator.hpp), `automatic` IDA for networks with an
// inerter (where fixed steps are only second order and the resonance of an internal mass
// needs many steps per cycle) or with series and parallel blocks alternating more than
// kFixedStepMaxBlockDepth deep (the fixed-step tree solver nests one Newton solve per level,
// so its cost grows geometrically with the depth: ~0.15 s per harmonic point at 3, ~10 s at 4),
// and the fixed-step kernels otherwise (exact for networks whose elements all sit in the root
// parallel block, first order in nested dashpots).
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

}  // namespace rheo::runtime
