#include "runtime/protocols/run_history.hpp"

#include "runtime/dae/dae_history_stepper.hpp"
#include "runtime/dae/dae_protocols.hpp"
#include "runtime/stepping/drive_stepper.hpp"
#include "runtime/stepping/relaxed_state.hpp"

#include <algorithm>

namespace rheo::runtime {

double start_on_ida(const Network& network, DaeHistoryStepper& stepper, double t0, double u0) {
  if (u0 == 0.0) return stepper.start(t0, u0);
  const StartAtRest start = relaxed_start(network, relaxed_state(network, u0));
  return stepper.start(t0, u0, &start);
}

History run_history(const Network& network, const Drive& drive, bool elements, SolverChoice solver) {
  const double u0 = drive.displacement.front();
  if (uses_sundials(network, solver)) {
    if (u0 == 0.0) return dae_history(network, drive, elements);
    const StartAtRest start = relaxed_start(network, relaxed_state(network, u0));
    return dae_history(network, drive, elements, nullptr, &start);  // as start_on_ida starts it
  }
  DriveStepper stepper(network, elements);
  History h;
  const std::size_t n = drive.time.size();
  h.time = drive.time;
  h.displacement = drive.displacement;
  h.force.assign(n, 0.0);
  const auto& probes = network.topology().probes;
  if (elements) {
    for (const auto& probe : probes) h.element_paths.push_back(probe.path);
    h.element_force.assign(probes.size(), std::vector<double>(n, 0.0));
    h.element_elongation.assign(probes.size(), std::vector<double>(n, 0.0));
  }
  for (std::size_t k = 0; k < n; ++k) {
    h.force[k] = k == 0 ? stepper.start(drive.time[0], u0) : stepper.step(drive.time[k], drive.displacement[k]);
    for (std::size_t i = 0; elements && i < probes.size(); ++i) {
      h.element_force[i][k] = stepper.element_force()[i];
      h.element_elongation[i][k] = stepper.element_elongation()[i];
    }
  }
  return h;
}

std::vector<double> history_force(const Network& network, const Drive& drive, SolverChoice solver) {
  if (uses_sundials(network, solver)) return run_history(network, drive, false, solver).force;
  DriveStepper stepper(network, false);
  std::vector<double> force(drive.time.size());
  for (std::size_t k = 0; k < force.size(); ++k)
    force[k] = k == 0 ? stepper.start(drive.time[0], drive.displacement[0]) : stepper.step(drive.time[k], drive.displacement[k]);
  return force;
}

HistoryForceStream::HistoryForceStream(const Network& network, const Drive& drive, SolverChoice solver) : network_(network), drive_(drive) {
  if (uses_sundials(network, solver)) ida_ = std::make_unique<DaeHistoryStepper>(network, false, DaeHistoryScales::of(drive));
  else stepper_ = std::make_unique<DriveStepper>(network, false);
}

HistoryForceStream::~HistoryForceStream() = default;
HistoryForceStream::HistoryForceStream(HistoryForceStream&&) noexcept = default;

std::size_t HistoryForceStream::next(std::span<double> out) {
  const std::size_t count = std::min(out.size(), drive_.time.size() - at_);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t k = at_ + i;
    const double t = drive_.time[k], u = drive_.displacement[k];
    if (stepper_) out[i] = k == 0 ? stepper_->start(t, u) : stepper_->step(t, u);
    else out[i] = k == 0 ? start_on_ida(network_, *ida_, t, u) : ida_->step(t, u);
  }
  at_ += count;
  return count;
}

}  // namespace rheo::runtime
