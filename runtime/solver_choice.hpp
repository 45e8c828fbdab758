// Which integrator steps a network: `fixed` the fixed-step kernels (simulator.hpp), `sundials`
// the variable-step IDA backend (dae_integrator.hpp), `automatic` IDA for networks with an
// inerter (where fixed steps are only second order and the resonance of an internal mass
// needs many steps per cycle) and the fixed-step kernels otherwise (exact for networks whose
// elements all sit in the root parallel block, first order in nested dashpots).
#pragma once

#include "runtime/network.hpp"

#include <optional>
#include <string_view>

namespace rheo::runtime {

enum class SolverChoice { automatic, fixed, sundials };

// Whether `choice` resolves to the SUNDIALS backend for this network.
bool uses_sundials(const Network& network, SolverChoice choice);

// "auto", "fixed", "sundials"; nullopt for anything else.
std::optional<SolverChoice> parse_solver_choice(std::string_view word);
const char* solver_word(SolverChoice choice);

}  // namespace rheo::runtime
