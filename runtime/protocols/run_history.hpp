// Runs a displacement drive through a network: the fixed-step simulator, or SUNDIALS IDA where
// the solver choice takes it (solver_choice.hpp).
#pragma once

#include "runtime/core/drive.hpp"
#include "runtime/network/network.hpp"
#include "runtime/protocols/solver_choice.hpp"

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace rheo::runtime {

// Simulates the drive from the relaxed state at its first displacement (stepping/relaxed_state.hpp;
// from 0 that is the rest state); sample 0 is that state. With `elements`, records every
// element's force and elongation.
History run_history(const Network& network, const Drive& drive, bool elements, SolverChoice solver = SolverChoice::automatic);
// Its force alone [N], one per drive sample, without copying the drive (fits score it at every
// evaluation).
std::vector<double> history_force(const Network& network, const Drive& drive, SolverChoice solver = SolverChoice::automatic);

class DriveStepper;       // stepping/drive_stepper.hpp
class DaeHistoryStepper;  // dae/dae_history_stepper.hpp

// Sample 0 of a history on IDA at time T0 [s] and displacement U0 [mm], started as every history
// on IDA starts (run_history, HistoryForceStream, stream_history.hpp): from rest at 0, else from
// the relaxed state at U0 (stepping/relaxed_state.hpp). Returns its force [N].
double start_on_ida(const Network& network, DaeHistoryStepper& stepper, double t0, double u0);

// history_force a block of samples at a time, the same numbers bit for bit, without holding
// them all (fits score long histories so): one step per sample as the blocks are asked for, on
// the fixed-step kernels or on IDA (dae_history_stepper.hpp). NETWORK and DRIVE must outlive
// the stream.
class HistoryForceStream {
 public:
  HistoryForceStream(const Network& network, const Drive& drive, SolverChoice solver = SolverChoice::automatic);
  ~HistoryForceStream();
  HistoryForceStream(HistoryForceStream&&) noexcept;
  HistoryForceStream& operator=(HistoryForceStream&&) = delete;
  HistoryForceStream(const HistoryForceStream&) = delete;
  HistoryForceStream& operator=(const HistoryForceStream&) = delete;

  // The forces [N] of the next samples into OUT, as many as it holds or are left; their count
  // (0 at the end). Throws what history_force throws.
  std::size_t next(std::span<double> out);

 private:
  const Network& network_;
  const Drive& drive_;
  std::unique_ptr<DriveStepper> stepper_;   // fixed steps; null where SUNDIALS took the network
  std::unique_ptr<DaeHistoryStepper> ida_;  // SUNDIALS; else null
  std::size_t at_ = 0;                      // samples handed out
};

}  // namespace rheo::runtime
