#include "runtime/protocols/run_history.hpp"

#include "runtime/dae/dae_protocols.hpp"
#include "runtime/stepping/relaxed_state.hpp"
#include "runtime/stepping/simulator.hpp"

#include <cmath>
#include <stdexcept>

namespace rheo::runtime {

History run_history(const Network& network, const Drive& drive, bool elements, SolverChoice solver) {
  const double u0 = drive.displacement.front();
  if (uses_sundials(network, solver)) {
    if (u0 == 0.0) return dae_history(network, drive, elements);
    const StartAtRest start = relaxed_start(network, relaxed_state(network, u0));
    return dae_history(network, drive, elements, nullptr, &start);
  }
  const Simulator simulator(network);
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
  State state = relaxed_state(network, u0), next = state;
  h.force[0] = state.force;
  if (elements && u0 != 0.0) {
    const StartAtRest start = relaxed_start(network, state);
    for (std::size_t i = 0; i < probes.size(); ++i) {
      h.element_force[i][0] = start.element_force[i];
      h.element_elongation[i][0] = start.element_elongation[i];
    }
  }
  StepPlan plan;
  std::vector<double> f, e;
  for (std::size_t k = 1; k < n; ++k) {
    const double dt = drive.time[k] - drive.time[k - 1];
    if (!(dt > 0.0)) throw std::logic_error("drive time must increase strictly");
    if (plan.dt == 0.0 || std::abs(dt - plan.dt) > 1e-9 * dt) plan = StepPlan::make(network, dt);
    h.force[k] = simulator.step(plan, state, drive.displacement[k], next, drive.time[k]);
    if (elements) {
      simulator.element_outputs(plan, state, next, f, e);
      for (std::size_t i = 0; i < probes.size(); ++i) {
        h.element_force[i][k] = f[i];
        h.element_elongation[i][k] = e[i];
      }
    }
    std::swap(state, next);
  }
  return h;
}

}  // namespace rheo::runtime
