#include "runtime/dae/dae_graph.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/network/leaf_kernels.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rheo::runtime {
namespace {

using lang::ElementKind;

struct GraphBuilder {
  const Network& network;
  DaeGraph& graph;

  double value(const lang::Element& e, int slot) const { return network.parameter(e.parameters[static_cast<std::size_t>(slot)]); }
  // The last slot: a slider's or friction element's compression yield force (fy, or fy_neg when given).
  static int last(const lang::Element& e) { return static_cast<int>(e.parameters.size()) - 1; }
  int new_node() { return graph.internal_nodes++; }

  lang::SourceLocation where;  // of the leaf being placed

  int add_edge(EdgeKind kind, int a, int b, std::initializer_list<double> p, const std::string& path) {
    Edge edge;
    edge.kind = kind;
    edge.a = a;
    edge.b = b;
    int i = 0;
    for (double v : p) edge.p[i++] = v;
    edge.path = path;
    edge.where = where;
    graph.edges.push_back(edge);
    return static_cast<int>(graph.edges.size()) - 1;
  }

  void place(const lang::Element& e, int a, int b) {
    switch (e.kind) {
      case ElementKind::parallel:
        for (const auto& child : e.children) place(child, a, b);
        return;
      case ElementKind::series: {
        int from = a;
        for (std::size_t i = 0; i < e.children.size(); ++i) {
          const int to = i + 1 == e.children.size() ? b : new_node();
          place(e.children[i], from, to);
          from = to;
        }
        return;
      }
      default: break;
    }
    EdgeProbe probe{e.path, {}, {}};
    where = e.where;
    switch (e.kind) {
      case ElementKind::spring: probe.edges = {add_edge(EdgeKind::spring, a, b, {value(e, 0)}, e.path)}; break;
      case ElementKind::yeoh: probe.edges = {add_edge(EdgeKind::yeoh, a, b, {value(e, 0), value(e, 1), value(e, 2)}, e.path)}; break;
      case ElementKind::dashpot: probe.edges = {add_edge(EdgeKind::dashpot, a, b, {value(e, 0)}, e.path)}; break;
      case ElementKind::quadratic_dashpot: probe.edges = {add_edge(EdgeKind::quadratic_dashpot, a, b, {value(e, 0)}, e.path)}; break;
      case ElementKind::inerter: probe.edges = {add_edge(EdgeKind::inerter, a, b, {value(e, 0)}, e.path)}; break;
      case ElementKind::bouc_wen: probe.edges = {add_edge(EdgeKind::bouc_wen, a, b, {value(e, 0), value(e, 1), value(e, 2)}, e.path)}; break;
      case ElementKind::slider: probe.edges = {add_edge(EdgeKind::slider, a, b, {value(e, 0), value(e, last(e))}, e.path)}; break;
      case ElementKind::gap:
        probe.edges = {add_edge(EdgeKind::gap, a, b, {0.5 * value(e, 0), gap_center(value(e, 0), value(e, 1))}, e.path)};
        break;
      case ElementKind::poly_spring: probe.edges = {add_edge(EdgeKind::poly_spring, a, b, {value(e, 0), value(e, 1), value(e, 2)}, e.path)}; break;
      case ElementKind::maxwell: {
        const int mid = new_node();
        probe.edges = {add_edge(EdgeKind::spring, a, mid, {value(e, 0)}, e.path), add_edge(EdgeKind::dashpot, mid, b, {value(e, 1)}, e.path)};
        break;
      }
      case ElementKind::friction: {
        const int mid = new_node();
        probe.edges = {add_edge(EdgeKind::spring, a, mid, {value(e, 0)}, e.path),
                       add_edge(EdgeKind::slider, mid, b, {value(e, 1), value(e, last(e))}, e.path)};
        break;
      }
      case ElementKind::springpot: place_springpot(e, a, b, probe); break;
      default: break;
    }
    if (probe.force_edges.empty()) probe.force_edges = {probe.edges.front()};
    graph.probes.push_back(std::move(probe));
  }

  // The modes are the compiled network's (derived parameters), so both backends share one chain.
  void place_springpot(const lang::Element& e, int a, int b, EdgeProbe& probe) {
    const auto& chains = network.topology().springpots;
    const auto chain = std::find_if(chains.begin(), chains.end(), [&](const SpringpotChain& c) { return c.path == e.path; });
    for (int j = 0; j < chain->modes; ++j) {
      const int mid = new_node();
      const int spring = add_edge(EdgeKind::spring, a, mid, {network.parameter(chain->first_derived + j)}, e.path);
      const int dashpot = add_edge(EdgeKind::dashpot, mid, b, {network.parameter(chain->first_derived + chain->modes + j)}, e.path);
      if (j == 0) probe.edges = {spring, dashpot};
      probe.force_edges.push_back(spring);
    }
  }
};

bool is_switch(EdgeKind kind) { return kind == EdgeKind::slider || kind == EdgeKind::gap; }

}  // namespace

DaeGraph DaeGraph::build(const Network& network) {
  DaeGraph graph;
  graph.model = network.model().name;
  GraphBuilder builder{network, graph, {}};
  builder.place(network.model().root, kTerminal, kGround);

  std::vector<int> held(static_cast<std::size_t>(graph.internal_nodes), 0);
  for (std::size_t i = 0; i < graph.edges.size(); ++i) {
    const Edge& edge = graph.edges[i];
    const int index = static_cast<int>(i);
    switch (edge.kind) {
      case EdgeKind::dashpot:
      case EdgeKind::quadratic_dashpot:
      case EdgeKind::inerter: graph.rate_edges.push_back(index); break;
      case EdgeKind::bouc_wen: graph.bouc_wen_edges.push_back(index); break;
      case EdgeKind::slider:
      case EdgeKind::gap: graph.switch_edges.push_back(index); break;
      default: break;
    }
    if (edge.kind == EdgeKind::inerter && edge.a < 0 && edge.b < 0)
      throw ModelError(
          fmt::format("{}inerter '{}' of model '{}' sits directly between the terminal and ground, so its force b d2u/dt2 needs the "
                      "drive's acceleration, which a sampled drive does not have; put it in series with a spring, or use solver = fixed",
                      error_at(edge.where), edge.path, graph.model));
    if (edge.kind == EdgeKind::slider && edge.a < 0 && edge.b < 0)  // (a gap there is refused by Network::compile)
      throw ModelError(
          fmt::format("{}slider '{}' of model '{}' sits directly between the terminal and ground, where the drive alone sets its "
                      "elongation, so IDA has no unknown to hold it stuck; put it in series with a spring (a friction element), or "
                      "use solver = fixed",
                      error_at(edge.where), edge.path, graph.model));
    if (!is_switch(edge.kind))
      for (int node : {edge.a, edge.b})
        if (node >= 0) held[static_cast<std::size_t>(node)] = 1;
  }
  if (!graph.switch_edges.empty())
    for (int index : graph.bouc_wen_edges) {
      const Edge& edge = graph.edges[static_cast<std::size_t>(index)];
      if (edge.a < 0 && edge.b < 0) continue;  // driven directly: its rate is the drive's
      throw ModelError(
          fmt::format("{}bouc_wen '{}' of model '{}' sits inside a block of a network with sliders, gaps or friction elements; its state's "
                      "rate follows node rates that jump when they switch, and IDA finds no consistent state there; use solver = fixed",
                      error_at(edge.where), edge.path, graph.model));
    }
  // Sliders in parallel (between the same two nodes) share one elongation: while both stick,
  // how they share the load is undetermined, so the mode's matrix is singular (IDACalcIC:
  // IDA_NO_RECOVERY). They act as one slider whose yield forces are their sums.
  for (std::size_t i = 0; i < graph.switch_edges.size(); ++i)
    for (std::size_t j = 0; j < i; ++j) {
      const Edge& first = graph.edges[static_cast<std::size_t>(graph.switch_edges[j])];
      const Edge& second = graph.edges[static_cast<std::size_t>(graph.switch_edges[i])];
      if (first.kind != EdgeKind::slider || second.kind != EdgeKind::slider) continue;
      if (!((first.a == second.a && first.b == second.b) || (first.a == second.b && first.b == second.a))) continue;
      const bool aligned = first.a == second.a;  // else the second's tension is the first's compression
      const double pos = first.p[0] + (aligned ? second.p[0] : second.p[1]), neg = first.p[1] + (aligned ? second.p[1] : second.p[0]);
      const std::string merged = pos == neg ? fmt::format("fy = {:g} N", pos) : fmt::format("fy_pos = {:g} N, fy_neg = {:g} N", pos, neg);
      throw ModelError(
          fmt::format("{}slider '{}' of model '{}' sits in parallel with slider '{}': while both stick, how they share the "
                      "force is undetermined, and IDA finds no consistent state; merge the sliders into one ({}), put a "
                      "spring in series with one of them (a friction element), or use solver = fixed",
                      error_at(second.where), second.path, graph.model, first.path, merged));
    }
  for (const Edge& edge : graph.edges)
    for (int node : {edge.a, edge.b})
      if (node >= 0 && !held[static_cast<std::size_t>(node)])
        throw ModelError(
            fmt::format("{}element '{}' of model '{}' meets another slider or gap at a node that nothing else holds, so the node's "
                        "position is undetermined while they slip; merge the sliders or put a spring between them",
                        error_at(edge.where), edge.path, graph.model));
  return graph;
}

std::vector<double> positions_at_rest(const DaeGraph& graph, double u0, const std::vector<double>& force, const std::vector<double>& elongation) {
  if (force.size() != graph.probes.size() || elongation.size() != graph.probes.size())
    throw std::logic_error("positions_at_rest: one force and elongation per element");
  const double unknown = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> edge_elongation(graph.edges.size(), unknown);
  for (std::size_t i = 0; i < graph.probes.size(); ++i) {
    const EdgeProbe& probe = graph.probes[i];
    const auto first = static_cast<std::size_t>(probe.edges.front());
    if (probe.edges.size() == 1) {
      edge_elongation[first] = elongation[i];
      continue;
    }
    const double spring = probe.force_edges.size() == 1 ? force[i] / graph.edges[first].p[0] : 0.0;
    edge_elongation[first] = spring;
    edge_elongation[static_cast<std::size_t>(probe.edges[1])] = elongation[i] - spring;
    for (std::size_t j = 1; j < probe.force_edges.size(); ++j) edge_elongation[static_cast<std::size_t>(probe.force_edges[j])] = 0.0;
  }
  // Walk the edges from the terminal and ground: e = x_a - x_b fixes one end from the other.
  std::vector<double> x(static_cast<std::size_t>(graph.internal_nodes), unknown);
  auto position = [&](int node) { return node == kTerminal ? u0 : node == kGround ? 0.0 : x[static_cast<std::size_t>(node)]; };
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t k = 0; k < graph.edges.size(); ++k) {
      const Edge& edge = graph.edges[k];
      const double e = edge_elongation[k], xa = position(edge.a), xb = position(edge.b);
      if (std::isnan(e) || std::isnan(xa) == std::isnan(xb)) continue;
      if (std::isnan(xa)) x[static_cast<std::size_t>(edge.a)] = xb + e;
      else x[static_cast<std::size_t>(edge.b)] = xa - e;
      changed = true;
    }
  }
  if (std::any_of(x.begin(), x.end(), [](double v) { return std::isnan(v); }))
    throw std::logic_error("positions_at_rest: a node no element's elongation reaches");
  return x;
}

double stiffest_spring_force(const DaeGraph& graph, double length) {
  double stiffest = 0.0;
  for (const Edge& edge : graph.edges)
    if (edge.kind == EdgeKind::spring || edge.kind == EdgeKind::yeoh || edge.kind == EdgeKind::poly_spring)
      stiffest = std::max(stiffest, (edge.kind == EdgeKind::yeoh ? 2.0 : 1.0) * std::abs(edge.p[0]) * length);
  return stiffest;
}

}  // namespace rheo::runtime
