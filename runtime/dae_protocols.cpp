#include "runtime/dae_protocols.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace rheo::runtime {

double dae_force_scale(const DaeGraph& graph, double length) {
  double scale = 0.0;
  for (const Edge& edge : graph.edges) {
    switch (edge.kind) {
      case EdgeKind::spring: scale += edge.p[0] * length; break;
      case EdgeKind::yeoh: scale += 2.0 * std::abs(edge.p[0]) * length; break;
      case EdgeKind::bouc_wen: scale += std::min(edge.p[2], edge.p[0] * length); break;
      case EdgeKind::slider: scale += edge.p[0]; break;
      default: break;
    }
  }
  return std::max(scale, 1e-6);
}

HarmonicPoint dae_harmonic_point(const Network& network, double amplitude, double frequency, const HarmonicOptions& options,
                                 DaeStatistics* statistics) {
  const DaeGraph graph = DaeGraph::build(network);
  const double omega = 2.0 * std::numbers::pi * frequency;
  DaeOptions dae;
  dae.relative_tolerance = kDaeRelativeTolerance;
  dae.length_scale = amplitude;
  dae.force_scale = dae_force_scale(graph, amplitude);
  dae.velocity_scale = omega * amplitude;
  DaeIntegrator integrator(graph, dae);
  integrator.start({DriveSignal::Kind::sine, amplitude, omega, nullptr});

  const int n = options.steps_per_cycle;
  const double period = 1.0 / frequency;
  const double tolerance = std::max(options.tolerance, 100.0 * kDaeRelativeTolerance);
  std::vector<double> phase(static_cast<std::size_t>(n)), displacement(phase.size()), force(phase.size());

  std::vector<double> start;
  HarmonicPoint point;
  point.amplitude = amplitude;
  point.frequency = frequency;
  double previous_change = std::numeric_limits<double>::infinity();
  for (int cycle = 1; cycle <= options.max_cycles; ++cycle) {
    start = integrator.state();  // reuses the capacity
    const double t0 = (cycle - 1) * period;
    for (int k = 0; k < n; ++k) {
      const double t = t0 + (k + 1) * period / n;
      const auto i = static_cast<std::size_t>(k);
      phase[i] = 2.0 * std::numbers::pi * (k + 1) / n;
      displacement[i] = amplitude * std::sin(phase[i]);
      force[i] = integrator.advance(t);
    }
    point.measures = measure_cycle(CycleSamples{phase, displacement, force}, amplitude, options.definition);
    point.cycles = cycle;
    const double force_scale = std::max(point.measures.force_amplitude, std::numeric_limits<double>::min());
    const double change = integrator.change_since(start, amplitude, force_scale, omega * amplitude);
    const double rate = change / previous_change;
    const double remaining = rate < 1.0 ? change * rate / (1.0 - rate) : change;
    previous_change = change;
    point.residual = std::max(change, remaining);
    if (cycle >= 2 && change <= tolerance && remaining <= tolerance) {
      point.converged = true;
      break;
    }
  }
  if (statistics) *statistics = integrator.statistics();
  return point;
}

History dae_history(const Network& network, const Drive& drive, bool elements, DaeStatistics* statistics) {
  const DaeGraph graph = DaeGraph::build(network);
  double length = 0.0;
  for (double u : drive.displacement) length = std::max(length, std::abs(u));
  length = std::max(length, 1e-6);
  const double duration = drive.time.back() - drive.time.front();
  DaeOptions dae;
  dae.relative_tolerance = kDaeRelativeTolerance;
  dae.length_scale = length;
  dae.force_scale = dae_force_scale(graph, length);
  dae.velocity_scale = duration > 0.0 ? length / duration : 1.0;
  DaeIntegrator integrator(graph, dae);
  integrator.start({DriveSignal::Kind::samples, 0.0, 0.0, &drive});

  History h;
  const std::size_t n = drive.time.size();
  h.time = drive.time;
  h.displacement = drive.displacement;
  h.force.assign(n, 0.0);
  if (elements) {
    for (const auto& probe : graph.probes) h.element_paths.push_back(probe.path);
    h.element_force.assign(graph.probes.size(), std::vector<double>(n, 0.0));
    h.element_elongation.assign(graph.probes.size(), std::vector<double>(n, 0.0));
  }
  std::vector<double> f, e;
  for (std::size_t k = 1; k < n; ++k) {
    h.force[k] = integrator.advance(drive.time[k]);
    if (elements) {
      integrator.element_outputs(f, e);
      for (std::size_t i = 0; i < graph.probes.size(); ++i) {
        h.element_force[i][k] = f[i];
        h.element_elongation[i][k] = e[i];
      }
    }
  }
  if (statistics) *statistics = integrator.statistics();
  return h;
}

}  // namespace rheo::runtime
