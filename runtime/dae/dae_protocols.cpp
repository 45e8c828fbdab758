#include "runtime/dae/dae_protocols.hpp"

#include "runtime/dae/dae_history_stepper.hpp"

#include "runtime/core/geometric_settling.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/network/leaf_kernels.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

namespace rheo::runtime {

namespace {

// What a subtree node carries at elongation `length` and rate `rate` (see dae_force_scale).
double node_force_scale(const Network& network, int node_index, double length, double rate) {
  const Topology& topology = network.topology();
  const TreeNode& node = topology.nodes[static_cast<std::size_t>(node_index)];
  const auto p = [&](int i) { return network.parameter(node.param[i]); };
  const double omega = rate / length;
  switch (node.kind) {
    case NodeKind::spring: return p(0) * length;
    case NodeKind::yeoh: return 2.0 * std::abs(p(0)) * length;
    case NodeKind::dashpot: return p(0) * rate;
    case NodeKind::quadratic_dashpot: return p(0) * rate * rate;
    case NodeKind::maxwell: return std::min(p(0) * length, p(1) * rate);
    case NodeKind::friction: return std::min(p(0) * length, 0.5 * (p(1) + p(2)));
    case NodeKind::slider: return 0.5 * (p(0) + p(1));
    case NodeKind::poly_spring: return p(0) * length;
    case NodeKind::inerter: return p(0) * omega * omega * length;
    case NodeKind::bouc_wen: return std::min(p(2), p(0) * length);
    case NodeKind::gap: return std::numeric_limits<double>::infinity();  // rigid in contact
    case NodeKind::parallel:
    case NodeKind::series: {
      const bool series = node.kind == NodeKind::series;
      double scale = series ? std::numeric_limits<double>::infinity() : 0.0;
      for (int c = 0; c < node.child_count; ++c) {
        const double child = node_force_scale(network, topology.children[static_cast<std::size_t>(node.first_child + c)], length, rate);
        scale = series ? std::min(scale, child) : scale + child;
      }
      return scale;
    }
  }
  return 0.0;
}

}  // namespace

double dae_force_scale(const Network& network, double length, double rate) {
  const Topology& t = network.topology();
  const auto p = [&](int i) { return network.parameter(i); };
  double scale = 0.0;
  for (int k : t.springs) scale += p(k) * length;
  for (const auto& y : t.yeohs) scale += 2.0 * std::abs(p(y[0])) * length;
  for (int c : t.dashpots) scale += p(c) * rate;
  for (const auto& m : t.maxwells) scale += std::min(p(m[0]) * length, p(m[1]) * rate);
  for (const auto& f : t.frictions) scale += std::min(p(f[0]) * length, p(f[1]));
  for (int s : t.sliders) scale += p(s);
  for (int root : t.subtrees) scale += node_force_scale(network, root, length, rate);
  return std::isfinite(scale) && scale > 1e-6 ? scale : 1e-6;
}

double dae_newton_tolerance(const DaeGraph& graph, double length, double force_scale) {
  const double stiffest = stiffest_spring_force(graph, length);
  constexpr double ida_default = 0.33, floor = 1e-6;
  return stiffest > 0.0 ? std::clamp(ida_default * force_scale / stiffest, floor, ida_default) : ida_default;
}

std::string dae_softening_hint(const Network& network) {
  const Topology& t = network.topology();
  std::string hint;
  for (const ElementProbe& probe : t.probes) {
    if (probe.source != ElementProbe::Source::tree_node) continue;
    const TreeNode& n = t.nodes[static_cast<std::size_t>(probe.index)];
    if (n.kind != NodeKind::yeoh) continue;
    const YeohLaw law{network.parameter(n.param[0]), network.parameter(n.param[1]), network.parameter(n.param[2])};
    const double e = law.softening_elongation();
    if (std::isfinite(e))
      hint += fmt::format(
          "{} yeoh '{}' softens to zero tangent stiffness at |e| = {:.6g} mm (carrying {:.6g} N), where a spring "
          "in series snaps through: keep its elongation below that, or {}",
          hint.empty() ? " Likely cause:" : ";", probe.path, e, std::abs(law.force(e)), YeohLaw::monotone_advice);
  }
  return hint;
}

std::vector<double> dae_start_positions(const Network& network, const DaeGraph& graph, double u0, const StartAtRest& start) {
  const auto& probes = network.topology().probes;
  if (probes.size() != graph.probes.size()) throw std::logic_error("dae: the graph's elements are not the network's");
  for (std::size_t i = 0; i < probes.size(); ++i)
    if (probes[i].path != graph.probes[i].path) throw std::logic_error("dae: element " + probes[i].path + " out of order in the graph");
  return positions_at_rest(graph, u0, start.element_force, start.element_elongation);
}

namespace {

constexpr double kSettlingNoise = 10.0 * kDaeRelativeTolerance;  // [-] of a component's scale

template <class Run>
auto with_softening_hint(const Network& network, Run run) {
  try {
    return run();
  } catch (const NumericalError& error) {
    throw NumericalError(error.what() + dae_softening_hint(network));
  }
}

HarmonicPoint harmonic_point(const Network& network, double amplitude, double frequency, const HarmonicOptions& options, DaeStatistics* statistics,
                             double preload, const StartAtRest* start) {
  const DaeGraph graph = DaeGraph::build(network);
  const double omega = 2.0 * std::numbers::pi * frequency;
  DaeOptions dae;
  dae.relative_tolerance = kDaeRelativeTolerance;
  dae.length_scale = amplitude;
  dae.force_scale = dae_force_scale(network, amplitude, omega * amplitude);
  dae.velocity_scale = omega * amplitude;
  dae.newton_tolerance = dae_newton_tolerance(graph, amplitude, dae.force_scale);
  DaeIntegrator integrator(graph, dae);
  const DriveSignal signal{DriveSignal::Kind::sine, amplitude, omega, nullptr, preload};
  if (preload != 0.0) {
    if (!start) throw std::logic_error("dae_harmonic_point: a preload needs the relaxed start");
    const std::vector<double> positions = dae_start_positions(network, graph, preload, *start);
    integrator.start(signal, &positions);
  } else if (const std::optional<DaeLinearStart> linear = dae_linear_periodic_start(graph, amplitude, omega)) {
    integrator.start(signal, *linear);
  } else {
    integrator.start(signal);
  }

  const int n = options.steps_per_cycle;
  const double period = 1.0 / frequency;
  const double tolerance = std::max(options.tolerance, 100.0 * kDaeRelativeTolerance);
  std::vector<double> phase(static_cast<std::size_t>(n)), displacement(phase.size()), force(phase.size());

  std::vector<double> cycle_start;
  HarmonicPoint point;
  point.amplitude = amplitude;
  point.frequency = frequency;
  double previous_change = std::numeric_limits<double>::infinity();
  StallWatch stall;
  // Slow tails (a springpot's chain behind a gap, a long Maxwell time) are skipped to their
  // geometric limits component by component, positions by the amplitude, Bouc-Wen states by 1,
  // where the distance left is above the tolerance; changes below ten times IDA's relative
  // tolerance are left alone (its own error is near them). The cycle after a skip is not taken as
  // converged: its change was measured from the moved state, its rate against the cycle before
  // the move.
  std::vector<double> settling_scales(static_cast<std::size_t>(graph.internal_nodes), amplitude);
  settling_scales.resize(integrator.settling_state().size(), 1.0);
  ComponentSettling settling(std::move(settling_scales), tolerance, kSettlingNoise);
  std::vector<double> skipped, cycle_state;
  int first_check = 1;
  for (int cycle = 1; cycle <= options.max_cycles; ++cycle) {
    cycle_start = integrator.state();  // reuses the capacity
    const double t0 = (cycle - 1) * period;
    for (int k = 0; k < n; ++k) {
      const double t = t0 + (k + 1) * period / n;
      const auto i = static_cast<std::size_t>(k);
      phase[i] = 2.0 * std::numbers::pi * (k + 1) / n;
      displacement[i] = preload + amplitude * std::sin(phase[i]);
      force[i] = integrator.advance(t);
    }
    point.measures = measure_cycle(CycleSamples{phase, displacement, force}, amplitude, options.definition);
    point.cycles = cycle;
    const double force_scale = std::max(point.measures.force_amplitude, std::numeric_limits<double>::min());
    const double change = integrator.change_since(cycle_start, amplitude, force_scale, omega * amplitude);
    const double rate = change / previous_change;
    const double remaining = rate < 1.0 ? change * rate / (1.0 - rate) : change;
    previous_change = change;
    point.residual = std::max(change, remaining);
    if (cycle >= 2 && cycle >= first_check && change <= tolerance && remaining <= tolerance) {
      point.converged = true;
      break;
    }
    if (cycle >= first_check) stall.add(cycle, options.max_cycles, change);  // not the cycle a skip ended
    point.stalled = cycle == options.max_cycles && stall.stalled(options.max_cycles);
    if (cycle < options.max_cycles && settling.record(integrator.settling_state(), skipped)) {
      cycle_state = integrator.settling_state();
      try {
        integrator.move_to(skipped);
        settling.forget();
        first_check = cycle + 2;
      } catch (const NumericalError&) {
        // No consistent state there (a drift taken for a slow contraction moved the nonlinear
        // springs far out): back to where the cycle ended, without moving those components again.
        integrator.move_to(cycle_state);
        settling.refuse_last();
      }
    }
  }
  point.skip_refused = settling.refused();
  if (statistics) *statistics = integrator.statistics();
  return point;
}

}  // namespace

HarmonicPoint dae_harmonic_point(const Network& network, double amplitude, double frequency, const HarmonicOptions& options,
                                 DaeStatistics* statistics, double preload, const StartAtRest* start) {
  return with_softening_hint(network, [&] { return harmonic_point(network, amplitude, frequency, options, statistics, preload, start); });
}

History dae_history(const Network& network, const Drive& drive, bool elements, DaeStatistics* statistics, const StartAtRest* start) {
  DaeHistoryStepper stepper(network, elements, DaeHistoryScales::of(drive));  // adds the softening hint to its failures
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
    h.force[k] = k == 0 ? stepper.start(drive.time[0], drive.displacement[0], start) : stepper.step(drive.time[k], drive.displacement[k]);
    for (std::size_t i = 0; elements && i < probes.size(); ++i) {
      h.element_force[i][k] = stepper.element_force()[i];
      h.element_elongation[i][k] = stepper.element_elongation()[i];
    }
  }
  if (statistics) *statistics = stepper.statistics();
  return h;
}

}  // namespace rheo::runtime
