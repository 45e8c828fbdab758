// The drive and the integration's way along it: starting, advancing to the next sample or output
// time, and sliding a sampled drive's window (dae_integrator.hpp). Part of DaeIntegrator, tested
// with it (tests/runtime/dae/dae_integrator_test.cpp, dae_history_stepper_test.cpp).
#include "runtime/dae/dae_integrator.hpp"

#include "runtime/dae/dae_integrator_detail.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rheo::runtime {

DaeIntegrator::DriveState DaeIntegrator::drive_at(double t) const {
  if (drive_.kind == DriveSignal::Kind::sine) {
    const double s = std::sin(drive_.omega * t), c = std::cos(drive_.omega * t);
    const double a = drive_.amplitude, w = drive_.omega;
    return {drive_.offset + a * s, a * w * c, -a * w * w * s};
  }
  const Drive& d = *drive_.samples;
  const std::size_t k = std::min(segment_, d.time.size() - 2);
  const double du = (d.displacement[k + 1] - d.displacement[k]) / (d.time[k + 1] - d.time[k]);
  return {d.displacement[k] + du * (t - d.time[k]), du, 0.0};
}

void DaeIntegrator::start(const DriveSignal& drive, const std::vector<double>* positions) {
  drive_ = drive;
  segment_ = 0;
  rate_jump_pending_ = false;
  time_ = drive.kind == DriveSignal::Kind::samples ? drive.samples->time.front() : 0.0;
  events_ = 0;
  totals_ = {};
  modes_.assign(static_cast<std::size_t>(layout_.switch_forces), 0);  // sliders stuck, gaps open
  held_.assign(static_cast<std::size_t>(layout_.switch_forces), 0.0);
  start_bouc_wen_directions();
  std::fill(y_.begin(), y_.end(), 0.0);
  std::fill(yp_.begin(), yp_.end(), 0.0);
  if (positions) {
    if (positions->size() != static_cast<std::size_t>(layout_.positions))
      throw std::logic_error("DaeIntegrator::start: one position per internal node");
    std::copy(positions->begin(), positions->end(), y_.begin());
    const DriveState at_start = drive_at(time_);
    for (int l = 0; l < layout_.switch_forces; ++l) {
      const Edge& edge = switch_edge(l);
      const double e = elongation(y_.data(), at_start, edge);
      if (edge.kind == EdgeKind::slider) {
        at(held_, l) = e;
      } else if (std::abs(e - edge.p[1]) >= edge.p[0] * (1.0 - 1e-12)) {  // a gap on its stop
        at(modes_, l) = e > edge.p[1] ? 1 : -1;
        at(held_, l) = gap_stop(edge, at(modes_, l));
      }
    }
  }
  kinematics_ = ModeKinematics::make(graph_, modes_);
  // The smallest step: 1e-13 of the drive's time scale (its duration, or 1/w). Without it, IDA's
  // corrector failing at every other step (a rate it predicts with the wrong sign, behind a
  // quadratic dashpot whose Newton tangent reads that rate) halved h down to 1e-19 s and took
  // 500000 steps there; below the floor the failure is returned, and solve_to restarts from
  // consistent rates.
  if (solver_) sundials::check_ida(IDASetMinStep(solver_->ida.get(), 1e-10 * time_horizon()), "IDASetMinStep");
  restart(time_, true);
}

void DaeIntegrator::start(const DriveSignal& drive, const DaeLinearStart& linear) {
  if (linear.rate_edge_rates.size() != graph_.rate_edges.size()) throw std::logic_error("DaeIntegrator::start: one rate per rate edge");
  start_rates_ = linear.rate_edge_rates;
  start(drive, &linear.positions);
}

double DaeIntegrator::time_horizon() const {
  return drive_.kind == DriveSignal::Kind::sine ? 1e-3 / std::max(drive_.omega, std::numeric_limits<double>::min())
         : drive_.duration > 0.0                ? 1e-3 * drive_.duration
                                                : 1e-3 * (drive_.samples->time.back() - drive_.samples->time.front());
}

void DaeIntegrator::slide(const Drive& window, std::size_t segment) {
  if (drive_.kind != DriveSignal::Kind::samples || window.time.size() < 2 || segment + 1 >= window.time.size())
    throw std::logic_error("DaeIntegrator::slide: a window of a sampled drive, holding the interval of the current time");
  drive_.samples = &window;
  segment_ = segment;
}

double DaeIntegrator::advance(double t) {
  const bool samples = drive_.kind == DriveSignal::Kind::samples;
  if (rate_jump_pending_) {  // the last advance ended on a sample; the next piece starts here
    rate_jump_pending_ = false;
    ++segment_;
    restart(time_, false);
    stick_reversed_sliders();
  }
  if (!solver_) {
    time_ = t;
    if (samples)
      while (segment_ + 2 < drive_.samples->time.size() && drive_.samples->time[segment_ + 1] < t) ++segment_;
  }
  while (solver_ && time_ < t) {
    double stop = t;
    const bool at_breakpoint = samples && segment_ + 2 < drive_.samples->time.size() && drive_.samples->time[segment_ + 1] <= t;
    if (at_breakpoint) stop = drive_.samples->time[segment_ + 1];
    solve_to(stop);
    if (at_breakpoint && time_ >= stop) {
      if (stop >= t) {  // the sample asked for: report it before the rate jumps (run_history.hpp)
        rate_jump_pending_ = true;
        break;
      }
      ++segment_;
      restart(time_, false);  // the drive rate jumps here
      stick_reversed_sliders();
    }
  }
  edge_forces(drive_at(time_), y_.data(), yp_.data(), force_.data());
  return terminal_force(force_.data());
}

}  // namespace rheo::runtime
