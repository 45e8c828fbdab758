#include "runtime/dae/dae_history_stepper.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/dae/dae_protocols.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rheo::runtime {
namespace {

// IDA's settings for a history: positions to rtol of the drive's reach (at least 1e-6 mm),
// rates to rtol of reach / duration, forces to rtol of what the network carries at those.
DaeOptions history_options(const Network& network, const DaeGraph& graph, const DaeHistoryScales& scales) {
  const double length = std::max(scales.reach, 1e-6);
  DaeOptions dae;
  dae.relative_tolerance = kDaeRelativeTolerance;
  dae.length_scale = length;
  dae.velocity_scale = scales.duration > 0.0 ? length / scales.duration : 1.0;
  dae.force_scale = dae_force_scale(network, length, dae.velocity_scale);
  dae.newton_tolerance = dae_newton_tolerance(graph, length, dae.force_scale);
  return dae;
}

}  // namespace

void DaeHistoryScales::add(double t, double u) {
  if (!started_) first_time_ = t, started_ = true;
  reach = std::max(reach, std::abs(u));
  duration = t - first_time_;
}

DaeHistoryScales DaeHistoryScales::of(const Drive& drive) {
  DaeHistoryScales scales;
  for (double u : drive.displacement) scales.reach = std::max(scales.reach, std::abs(u));
  if (!drive.time.empty()) scales.duration = drive.time.back() - drive.time.front();
  return scales;
}

DaeHistoryStepper::DaeHistoryStepper(const Network& network, bool elements, const DaeHistoryScales& scales)
    : network_(network), graph_(DaeGraph::build(network)), duration_(scales.duration), elements_(elements) {
  integrator_ = std::make_unique<DaeIntegrator>(graph_, history_options(network, graph_, scales));
  window_.time.reserve(4);
  window_.displacement.reserve(4);
  if (elements_) {
    element_force_.assign(graph_.probes.size(), 0.0);
    element_elongation_.assign(graph_.probes.size(), 0.0);
  }
}

DaeHistoryStepper::~DaeHistoryStepper() = default;

double DaeHistoryStepper::start(double t0, double u0, const StartAtRest* start) {
  window_.time.assign(1, t0);
  window_.displacement.assign(1, u0);
  taken_ = 1;
  positions_.clear();
  if (!start) {
    std::fill(element_force_.begin(), element_force_.end(), 0.0);
    std::fill(element_elongation_.begin(), element_elongation_.end(), 0.0);
    return 0.0;
  }
  positions_ = dae_start_positions(network_, graph_, u0, *start);
  if (elements_) element_force_ = start->element_force, element_elongation_ = start->element_elongation;
  return start->force;
}

double DaeHistoryStepper::step(double t, double u) {
  if (taken_ == 0) throw std::logic_error("DaeHistoryStepper::step before start");
  try {
    // The window: up to two samples before the newest, the newest (t, u), and a look-ahead.
    if (window_.time.size() == 4) {  // drop the oldest and the look-ahead
      window_.time.erase(window_.time.begin()), window_.displacement.erase(window_.displacement.begin());
      window_.time.pop_back(), window_.displacement.pop_back();
    } else if (window_.time.size() == 3) {
      window_.time.pop_back(), window_.displacement.pop_back();
    }
    const double before = window_.time.back();
    window_.time.push_back(t), window_.displacement.push_back(u);
    const double ahead = t + (t - before);
    window_.time.push_back(ahead > t ? ahead : std::nextafter(t, std::numeric_limits<double>::infinity()));
    window_.displacement.push_back(u);
    if (taken_ == 1) {
      const DriveSignal signal{DriveSignal::Kind::samples, 0.0, 0.0, &window_, 0.0, duration_};
      if (positions_.empty()) integrator_->start(signal);
      else integrator_->start(signal, &positions_);
    } else {
      integrator_->slide(window_, 0);  // interval 0 ends at the last sample, where the integration stands
    }
    ++taken_;
    const double force = integrator_->advance(t);
    if (elements_) integrator_->element_outputs(element_force_, element_elongation_);
    return force;
  } catch (const NumericalError& error) {
    throw NumericalError(error.what() + dae_softening_hint(network_));
  }
}

}  // namespace rheo::runtime
