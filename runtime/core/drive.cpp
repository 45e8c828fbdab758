#include "runtime/core/drive.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rheo::runtime {
namespace {

void start(Drive& d) {
  d.time.assign(1, 0.0);
  d.displacement.assign(1, 0.0);
}

}  // namespace

Drive static_triangle(const std::vector<double>& amplitudes, double velocity, int cycles, int steps_per_cycle) {
  Drive d;
  start(d);
  const int quarter = steps_per_cycle / 4;
  for (double amplitude : amplitudes) {
    const double dt = amplitude / (quarter * velocity);
    const double t0 = d.time.back();
    for (int k = 1; k <= cycles * steps_per_cycle; ++k) {
      const int in_cycle = k % steps_per_cycle;
      // Unit triangle over one cycle: 0 -> 1 -> 0 -> -1 -> 0.
      const double s = static_cast<double>(in_cycle) / quarter;
      const double shape = s <= 1.0 ? s : s <= 3.0 ? 2.0 - s : s - 4.0;
      d.time.push_back(t0 + k * dt);
      d.displacement.push_back(amplitude * shape);
    }
  }
  return d;
}

Drive quasistatic_sine(const std::vector<double>& amplitudes, double frequency, int cycles, int steps_per_cycle) {
  Drive d;
  start(d);
  const double dt = 1.0 / (frequency * steps_per_cycle);
  for (double amplitude : amplitudes) {
    const double t0 = d.time.back();
    for (int k = 1; k <= cycles * steps_per_cycle; ++k) {
      const int in_cycle = k % steps_per_cycle;
      d.time.push_back(t0 + k * dt);
      d.displacement.push_back(amplitude * std::sin(2.0 * std::numbers::pi * in_cycle / steps_per_cycle));
    }
  }
  return d;
}

Drive step_relaxation(double amplitude, double rise, double duration, double dt) {
  Drive d;
  start(d);
  const auto samples = static_cast<long>(std::ceil(duration / dt - 1e-9));
  for (long k = 1; k <= samples; ++k) {
    const double t = std::min(duration, static_cast<double>(k) * dt);
    d.time.push_back(t);
    d.displacement.push_back(t >= rise ? amplitude : amplitude * t / rise);
  }
  return d;
}

Drive refine(const Drive& drive, int substeps) {
  if (substeps <= 1) return drive;
  Drive d;
  start(d);
  d.time[0] = drive.time[0];
  d.displacement[0] = drive.displacement[0];
  for (std::size_t k = 1; k < drive.time.size(); ++k)
    for (int s = 1; s <= substeps; ++s) {
      const double w = static_cast<double>(s) / substeps;
      d.time.push_back(drive.time[k - 1] + w * (drive.time[k] - drive.time[k - 1]));
      d.displacement.push_back(drive.displacement[k - 1] + w * (drive.displacement[k] - drive.displacement[k - 1]));
    }
  return d;
}

}  // namespace rheo::runtime
