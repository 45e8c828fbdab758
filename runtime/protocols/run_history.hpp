// Runs a displacement drive through a network: the fixed-step simulator, or SUNDIALS IDA where
// the solver choice takes it (solver_choice.hpp).
#pragma once

#include "runtime/core/drive.hpp"
#include "runtime/network/network.hpp"
#include "runtime/protocols/solver_choice.hpp"

namespace rheo::runtime {

// Simulates the drive from the relaxed state at its first displacement (stepping/relaxed_state.hpp;
// from 0 that is the rest state); sample 0 is that state. With `elements`, records every
// element's force and elongation.
History run_history(const Network& network, const Drive& drive, bool elements, SolverChoice solver = SolverChoice::automatic);
// Its force alone [N], one per drive sample, without copying the drive (fits score it at every
// evaluation).
std::vector<double> history_force(const Network& network, const Drive& drive, SolverChoice solver = SolverChoice::automatic);

}  // namespace rheo::runtime
