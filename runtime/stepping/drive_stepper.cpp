#include "runtime/stepping/drive_stepper.hpp"

#include "runtime/stepping/relaxed_state.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace rheo::runtime {

DriveStepper::DriveStepper(const Network& network, bool elements) : network_(network), simulator_(network), elements_(elements) {
  const std::size_t probes = elements ? network.topology().probes.size() : 0;
  element_force_.assign(probes, 0.0);
  element_elongation_.assign(probes, 0.0);
}

double DriveStepper::start(double t0, double u0) {
  state_ = relaxed_state(network_, u0);
  next_ = state_;
  time_ = t0;
  plan_ = StepPlan{};
  if (elements_ && u0 != 0.0) {
    const StartAtRest start = relaxed_start(network_, state_);
    element_force_ = start.element_force;
    element_elongation_ = start.element_elongation;
  } else {
    std::fill(element_force_.begin(), element_force_.end(), 0.0);
    std::fill(element_elongation_.begin(), element_elongation_.end(), 0.0);
  }
  return state_.force;
}

double DriveStepper::step(double t, double u) {
  const double dt = t - time_;
  if (!(dt > 0.0)) throw std::logic_error("drive time must increase strictly");
  if (plan_.dt == 0.0 || std::abs(dt - plan_.dt) > 1e-9 * dt) plan_ = StepPlan::make(network_, dt);
  const double force = simulator_.step(plan_, state_, u, next_, t);
  if (elements_) simulator_.element_outputs(plan_, state_, next_, element_force_, element_elongation_);
  std::swap(state_, next_);
  time_ = t;
  return force;
}

}  // namespace rheo::runtime
