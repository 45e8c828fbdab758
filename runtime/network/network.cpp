#include "runtime/network/network.hpp"

#include "lang/limits.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/network/springpot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>

namespace rheo::runtime {
namespace {

using lang::ElementKind;

// Mutable intermediate tree used only while compiling.
struct Proto {
  NodeKind kind = NodeKind::parallel;
  int param[3] = {-1, -1, -1};
  int probe = -1;                // user element this leaf stands for
  int fused_dashpot_probe = -1;  // a fused spring+dashpot pair: the dashpot's probe
  lang::SourceLocation where;    // of the element, for messages
  bool opaque = false;           // a block standing for one user element (a springpot chain)
  bool one_sided = false;        // a friction element or slider given fy_pos and fy_neg
  std::vector<Proto> children;
  bool is_block() const { return kind == NodeKind::parallel || kind == NodeKind::series; }
};

NodeKind node_kind(ElementKind kind) {
  switch (kind) {
    case ElementKind::spring: return NodeKind::spring;
    case ElementKind::yeoh: return NodeKind::yeoh;
    case ElementKind::dashpot: return NodeKind::dashpot;
    case ElementKind::maxwell: return NodeKind::maxwell;
    case ElementKind::friction: return NodeKind::friction;
    case ElementKind::slider: return NodeKind::slider;
    case ElementKind::inerter: return NodeKind::inerter;
    case ElementKind::quadratic_dashpot: return NodeKind::quadratic_dashpot;
    case ElementKind::gap: return NodeKind::gap;
    case ElementKind::bouc_wen: return NodeKind::bouc_wen;
    case ElementKind::poly_spring: return NodeKind::poly_spring;
    case ElementKind::springpot:
    case ElementKind::parallel: return NodeKind::parallel;
    case ElementKind::series: return NodeKind::series;
  }
  return NodeKind::parallel;
}

struct Converter {
  Topology& topology;
  const lang::CheckedModel& model;

  Proto convert(const lang::Element& element) {
    Proto proto;
    proto.kind = node_kind(element.kind);
    if (element.kind != ElementKind::springpot && proto.is_block()) {
      for (const auto& child : element.children) proto.children.push_back(convert(child));
      return proto;
    }
    for (std::size_t i = 0; i < element.parameters.size() && i < 3; ++i) proto.param[i] = element.parameters[i];
    // The compression yield force's slot (network.hpp): fy again when given symmetric.
    const std::size_t yields = element.kind == ElementKind::friction ? 2 : element.kind == ElementKind::slider ? 1 : 0;
    if (yields > 0) {
      proto.one_sided = element.parameters.size() > yields;
      if (!proto.one_sided) proto.param[yields] = proto.param[yields - 1];
    }
    proto.probe = static_cast<int>(topology.probes.size());
    proto.where = element.where;
    topology.probes.push_back({element.path, element.kind, ElementProbe::Source::tree_node, 0});
    if (element.kind == ElementKind::springpot) add_springpot_chain(element, proto);
    return proto;
  }

  // The chain's modes as Maxwell children with derived parameter indices (network.hpp).
  void add_springpot_chain(const lang::Element& element, Proto& proto) {
    SpringpotChain chain;
    for (int i = 0; i < 5; ++i) chain.param[i] = element.parameters[static_cast<std::size_t>(i)];
    auto value = [&](int slot) { return model.parameters[static_cast<std::size_t>(chain.param[slot])].value; };
    if (!(value(3) < value(4)))
      throw ModelError(
          fmt::format("{}model '{}': springpot '{}' has f_low = {:g} Hz not below f_high = {:g} Hz; give a band "
                      "f_low < f_high covering the frequencies you simulate",
                      error_at(element.where), model.name, element.path, value(3), value(4)));
    // The band sets the chain's length (4 modes per decade): within the frequency range of
    // lang/limits.hpp it has at most about 180 modes and every relaxation time is finite.
    if (!(value(3) >= lang::min_frequency && value(4) <= lang::max_frequency))
      throw ModelError(
          fmt::format("{}model '{}': springpot '{}' has the band {:g} to {:g} Hz, beyond the frequencies rheo simulates ({:g} to "
                      "{:g} Hz, lang/limits.hpp); give f_low and f_high within them",
                      error_at(element.where), model.name, element.path, value(3), value(4), lang::min_frequency, lang::max_frequency));
    chain.path = element.path;
    chain.modes = springpot_mode_count(value(3), value(4));
    chain.first_derived = static_cast<int>(model.parameters.size()) + topology.derived_parameters;
    topology.derived_parameters += 2 * chain.modes;
    proto.opaque = true;
    for (int j = 0; j < chain.modes; ++j) {
      Proto mode;
      mode.kind = NodeKind::maxwell;
      mode.param[0] = chain.first_derived + j;
      mode.param[1] = chain.first_derived + chain.modes + j;
      mode.where = element.where;
      proto.children.push_back(mode);
    }
    topology.springpots.push_back(chain);
  }
};

void fuse_spring_dashpot(Proto& series) {
  int spring = -1, dashpot = -1, springs = 0, dashpots = 0;
  for (std::size_t i = 0; i < series.children.size(); ++i) {
    if (series.children[i].kind == NodeKind::spring) {
      spring = static_cast<int>(i);
      ++springs;
    }
    if (series.children[i].kind == NodeKind::dashpot) {
      dashpot = static_cast<int>(i);
      ++dashpots;
    }
  }
  if (springs != 1 || dashpots != 1) return;
  Proto pair;
  pair.kind = NodeKind::maxwell;
  pair.param[0] = series.children[static_cast<std::size_t>(spring)].param[0];
  pair.param[1] = series.children[static_cast<std::size_t>(dashpot)].param[0];
  pair.probe = series.children[static_cast<std::size_t>(spring)].probe;
  pair.fused_dashpot_probe = series.children[static_cast<std::size_t>(dashpot)].probe;
  std::vector<Proto> rest{pair};
  for (std::size_t i = 0; i < series.children.size(); ++i)
    if (static_cast<int>(i) != spring && static_cast<int>(i) != dashpot) rest.push_back(std::move(series.children[i]));
  series.children = std::move(rest);
}

Proto canonicalise(Proto proto) {
  if (!proto.is_block() || proto.opaque) return proto;
  std::vector<Proto> flat;
  for (auto& child : proto.children) {
    Proto c = canonicalise(std::move(child));
    if (c.kind == proto.kind && !c.opaque) {
      for (auto& grandchild : c.children) flat.push_back(std::move(grandchild));
    } else {
      flat.push_back(std::move(c));
    }
  }
  proto.children = std::move(flat);
  if (proto.kind == NodeKind::series) fuse_spring_dashpot(proto);
  if (proto.children.size() == 1) return std::move(proto.children.front());
  return proto;
}

struct TreeBuilder {
  Topology& topology;
  int next_state;

  // Appends the subtree rooted at proto; returns its node index. `prescribed`: a root-block
  // inerter, whose elongation is the drive.
  int add(const Proto& proto, bool prescribed = false) {
    const int index = static_cast<int>(topology.nodes.size());
    topology.nodes.push_back({});
    TreeNode node;
    node.kind = proto.kind;
    for (int i = 0; i < 3; ++i) node.param[i] = proto.param[i];
    node.drive_prescribed = prescribed && proto.kind == NodeKind::inerter;
    node.state = next_state;
    node.slots = proto.kind != NodeKind::inerter ? 2 : node.drive_prescribed ? 6 : 3;
    next_state += node.slots;
    using S = StateScale;
    topology.state_scales.insert(topology.state_scales.end(), {S::length, S::force});
    if (node.slots == 3) topology.state_scales.push_back(S::velocity);
    if (node.slots == 6) topology.state_scales.insert(topology.state_scales.end(), {S::velocity, S::velocity, S::time, S::time});
    if (proto.probe >= 0) {
      auto& probe = topology.probes[static_cast<std::size_t>(proto.probe)];
      probe.index = index;
      probe.source = proto.fused_dashpot_probe >= 0 ? ElementProbe::Source::tree_maxwell_spring : ElementProbe::Source::tree_node;
      if (proto.fused_dashpot_probe >= 0) {
        auto& dashpot = topology.probes[static_cast<std::size_t>(proto.fused_dashpot_probe)];
        dashpot.index = index;
        dashpot.source = ElementProbe::Source::tree_maxwell_dashpot;
      }
    }
    std::vector<int> kids;
    for (const auto& child : proto.children) kids.push_back(add(child));
    node.first_child = static_cast<int>(topology.children.size());
    node.child_count = static_cast<int>(kids.size());
    topology.children.insert(topology.children.end(), kids.begin(), kids.end());
    if (proto.kind == NodeKind::series) topology.internal_nodes += node.child_count - 1;
    node.linear = proto.kind == NodeKind::spring || proto.kind == NodeKind::dashpot || proto.kind == NodeKind::maxwell ||
                  proto.kind == NodeKind::inerter || proto.is_block();
    for (int k : kids) node.linear &= topology.nodes[static_cast<std::size_t>(k)].linear;
    node.capped_linear = proto.kind == NodeKind::series && !node.linear;
    for (int k : kids) {
      const TreeNode& kid = topology.nodes[static_cast<std::size_t>(k)];
      node.capped_linear &= kid.linear || kid.kind == NodeKind::friction || kid.kind == NodeKind::slider;
    }
    switch (proto.kind) {
      case NodeKind::slider: node.rigid_when_stuck = true; break;
      case NodeKind::parallel:
        for (int k : kids) node.rigid_when_stuck |= topology.nodes[static_cast<std::size_t>(k)].rigid_when_stuck;
        break;
      case NodeKind::series:
        node.rigid_when_stuck = true;
        for (int k : kids) node.rigid_when_stuck &= topology.nodes[static_cast<std::size_t>(k)].rigid_when_stuck;
        break;
      default: break;
    }
    topology.nodes[static_cast<std::size_t>(index)] = node;
    return index;
  }
};

// A force jump with the drive rate needs a dashpot reachable from the terminal without a
// compliant (spring-like) member in series. Sliders, gaps and inerters in series pass a rate
// jump on (rigid while stuck, in contact, or to a velocity jump). An inerter's own force is
// an estimate at the step end (leaf_kernels.hpp), so it does not ask for midpoint sampling.
bool rate_jump(const Proto& p) {
  switch (p.kind) {
    case NodeKind::dashpot:
    case NodeKind::quadratic_dashpot: return true;
    case NodeKind::parallel:
      for (const auto& c : p.children)
        if (rate_jump(c)) return true;
      return false;
    case NodeKind::series: {
      bool any = false;
      for (const auto& c : p.children) {
        if (c.kind == NodeKind::slider || c.kind == NodeKind::gap || c.kind == NodeKind::inerter) continue;
        if (!rate_jump(c)) return false;
        any = true;
      }
      return any;
    }
    default: return false;
  }
}

// See network.hpp: members that take up a velocity jump of their ends with a bounded force.
bool compliant(const Proto& p) {
  switch (p.kind) {
    case NodeKind::slider:
    case NodeKind::gap:
    case NodeKind::inerter: return false;
    case NodeKind::parallel:
      for (const auto& c : p.children)
        if (!compliant(c)) return false;
      return true;
    case NodeKind::series:
      for (const auto& c : p.children)
        if (compliant(c)) return true;
      return false;
    default: return true;
  }
}

// Enforces the placement rules of network.hpp. `driven`: nothing compliant lies in series
// between p and the drive; `root_level`: p is a leaf of the root parallel block.
struct PlacementCheck {
  const lang::CheckedModel& model;
  const std::vector<ElementProbe>& probes;

  const std::string& path(const Proto& p) const { return probes[static_cast<std::size_t>(p.probe)].path; }
  // The element's own name (the last part of its path), as it is written in its statement.
  std::string local_name(const Proto& p) const { return path(p).substr(path(p).rfind('.') + 1); }
  double value(const Proto& p) const { return model.parameters[static_cast<std::size_t>(p.param[0])].value; }

  [[noreturn]] void gap_error(const Proto& p, const char* where) const {
    throw ModelError(
        fmt::format("{}model '{}': gap '{}' {}; a gap must be in series with a compliant element (a spring, yeoh, poly_spring, dashpot, "
                    "maxwell, friction, bouc_wen or quadratic_dashpot): write series {{ gap {} (width = {:g} mm)  spring (k = 500 N/mm) }} "
                    "with the stiffness the gap engages",
                    error_at(p.where), model.name, path(p), where, local_name(p), value(p)));
  }
  [[noreturn]] void inerter_error(const Proto& p) const {
    throw ModelError(
        fmt::format("{}model '{}': inerter '{}' is connected to the drive through sliders, gaps or inerters only (or parallel "
                    "blocks holding one), so a change of the drive velocity while they hold would be an impact (an unbounded "
                    "force); put a compliant element (a spring, dashpot, maxwell, ...) in series with it, e.g. "
                    "series {{ spring (k = 500 N/mm)  inerter {} (b = {:g} N*s^2/mm) }} with a stiffness of your own, or place it directly in "
                    "the model's parallel block",
                    error_at(p.where), model.name, path(p), local_name(p), value(p)));
  }

  void visit(const Proto& p, bool driven, bool root_level) const {
    switch (p.kind) {
      case NodeKind::gap: gap_error(p, root_level ? "is in the model's parallel block" : "is inside a parallel block");
      case NodeKind::inerter:
        if (driven && !root_level) inerter_error(p);
        return;
      case NodeKind::parallel:
        for (const auto& c : p.children) visit(c, driven, false);
        return;
      case NodeKind::series: {
        int compliant_members = 0;
        for (const auto& c : p.children) compliant_members += compliant(c) ? 1 : 0;
        for (const auto& c : p.children) {
          if (c.kind == NodeKind::gap) {
            if (compliant_members == 0)
              gap_error(c, "is in a series chain with no compliant member (only sliders, gaps, inerters, or parallel blocks holding one)");
            continue;
          }
          const int others = compliant_members - (compliant(c) ? 1 : 0);
          visit(c, driven && others == 0, false);
        }
        return;
      }
      default: return;
    }
  }
};

template <class ParameterAt>
Coefficients make_coefficients(const Topology& t, ParameterAt at) {
  Coefficients c;
  for (int k : t.springs) c.spring_k += at(k);
  for (int d : t.dashpots) c.dashpot_c += at(d);
  for (const auto& y : t.yeohs) {
    c.yeoh_d10.push_back(at(y[0]));
    c.yeoh_d20.push_back(at(y[1]));
    c.yeoh_d30.push_back(at(y[2]));
  }
  for (const auto& m : t.maxwells) {
    c.maxwell_k.push_back(at(m[0]));
    c.maxwell_c.push_back(at(m[1]));
  }
  for (const auto& f : t.frictions) {
    c.friction_k.push_back(at(f[0]));
    c.friction_fy.push_back(at(f[1]));
  }
  for (int s : t.sliders) {
    c.slider_fy.push_back(at(s));
    c.slider_fy_total += at(s);
  }
  return c;
}

}  // namespace

Network Network::compile(const lang::CheckedModel& model) {
  auto topology = std::make_shared<Topology>();
  Proto root = canonicalise(Converter{*topology, model}.convert(model.root));
  topology->has_rate_jump = rate_jump(root);

  std::vector<Proto> branches;
  if (root.kind == NodeKind::parallel && !root.opaque) branches = std::move(root.children);  // a lone springpot is one branch
  else branches.push_back(std::move(root));
  const PlacementCheck placement{model, topology->probes};
  for (const auto& b : branches) placement.visit(b, true, !b.is_block());

  std::vector<const Proto*> trees;
  for (const auto& b : branches) {
    auto group = [&](ElementProbe::Source source, int index) {
      auto& probe = topology->probes[static_cast<std::size_t>(b.probe)];
      probe.source = source;
      probe.index = index;
    };
    switch (b.kind) {
      case NodeKind::spring:
        group(ElementProbe::Source::root_spring, static_cast<int>(topology->springs.size()));
        topology->springs.push_back(b.param[0]);
        break;
      case NodeKind::yeoh:
        group(ElementProbe::Source::root_yeoh, static_cast<int>(topology->yeohs.size()));
        topology->yeohs.push_back({b.param[0], b.param[1], b.param[2]});
        break;
      case NodeKind::dashpot:
        group(ElementProbe::Source::root_dashpot, static_cast<int>(topology->dashpots.size()));
        topology->dashpots.push_back(b.param[0]);
        break;
      case NodeKind::maxwell:
        if (b.fused_dashpot_probe >= 0) {
          trees.push_back(&b);
          break;
        }
        group(ElementProbe::Source::root_maxwell, static_cast<int>(topology->maxwells.size()));
        topology->maxwells.push_back({b.param[0], b.param[1]});
        break;
      case NodeKind::friction:
        if (b.one_sided) {
          trees.push_back(&b);
          break;
        }
        group(ElementProbe::Source::root_friction, static_cast<int>(topology->frictions.size()));
        topology->frictions.push_back({b.param[0], b.param[1]});
        break;
      case NodeKind::slider:
        if (b.one_sided) {
          trees.push_back(&b);
          break;
        }
        group(ElementProbe::Source::root_slider, static_cast<int>(topology->sliders.size()));
        topology->sliders.push_back(b.param[0]);
        break;
      case NodeKind::parallel:
        if (!b.opaque) {
          trees.push_back(&b);
          break;
        }
        group(ElementProbe::Source::root_springpot, static_cast<int>(topology->maxwells.size()));
        topology->probes[static_cast<std::size_t>(b.probe)].count = static_cast<int>(b.children.size());
        for (const auto& mode : b.children) topology->maxwells.push_back({mode.param[0], mode.param[1]});
        break;
      default: trees.push_back(&b); break;
    }
  }
  TreeBuilder builder{*topology, topology->slider_state() + static_cast<int>(topology->sliders.size())};
  topology->state_scales.assign(static_cast<std::size_t>(builder.next_state), StateScale::force);
  for (const Proto* tree : trees) topology->subtrees.push_back(builder.add(*tree, true));
  topology->state_size = builder.next_state;
  topology->is_linear = topology->yeohs.empty() && topology->frictions.empty() && topology->sliders.empty() &&
                        std::all_of(topology->subtrees.begin(), topology->subtrees.end(),
                                    [&](int n) { return topology->nodes[static_cast<std::size_t>(n)].linear; });

  Network network;
  network.model_ = std::make_shared<const lang::CheckedModel>(model);
  network.topology_ = std::move(topology);
  network.parameters_.reserve(model.parameters.size());
  for (const auto& parameter : model.parameters) network.parameters_.push_back(parameter.value);
  network.derive();
  network.check_gap_centres();
  return network;
}

void Network::derive() {
  const Topology& t = *topology_;
  derived_.assign(static_cast<std::size_t>(t.derived_parameters), 0.0);
  const auto own = static_cast<int>(parameters_.size());
  for (const auto& chain : t.springpots) {
    auto at = [&](int slot) { return parameters_[static_cast<std::size_t>(chain.param[slot])]; };
    if (!(at(3) < at(4)))  // compile() checked the written values: these are a fit's, within the bounds
      throw ModelError(
          fmt::format("{}model '{}': springpot '{}' would have f_low = {:g} Hz not below f_high = {:g} Hz; give f_low and "
                      "f_high bounds that do not overlap",
                      error_at(model_->parameters[static_cast<std::size_t>(chain.param[3])].where), model_->name, chain.path, at(3), at(4)));
    if (!(at(3) >= lang::min_frequency && at(4) <= lang::max_frequency))
      throw ModelError(
          fmt::format("{}model '{}': springpot '{}' would have the band {:g} to {:g} Hz, beyond the frequencies rheo "
                      "simulates ({:g} to {:g} Hz); give f_low and f_high bounds within them",
                      error_at(model_->parameters[static_cast<std::size_t>(chain.param[3])].where), model_->name, chain.path, at(3), at(4),
                      lang::min_frequency, lang::max_frequency));
    const auto modes = static_cast<std::size_t>(chain.modes);
    const std::span<double> stiffness(derived_.data() + (chain.first_derived - own), modes);
    springpot_modes({at(0), at(1), at(2), at(3), at(4)}, stiffness, {stiffness.data() + modes, modes});
  }
  coefficients_ = make_coefficients(t, [this](int i) { return parameter(i); });
}

void Network::check_gap_centres() const {
  const Topology& t = *topology_;
  for (std::size_t i = 0; i < t.nodes.size(); ++i) {
    const TreeNode& n = t.nodes[i];
    if (n.kind != NodeKind::gap) continue;
    const double width = parameter(n.param[0]), center = parameter(n.param[1]);
    if (std::abs(center) <= 0.5 * width * (1.0 + 1e-12)) continue;
    std::string path = "?";
    for (const auto& probe : t.probes)
      if (probe.source == ElementProbe::Source::tree_node && probe.index == static_cast<int>(i)) path = probe.path;
    throw ModelError(
        fmt::format("{}model '{}': gap '{}' has center = {:g} mm, beyond half its width ({:g} mm): its rest position "
                    "(e = 0) must lie in its play, |center| <= width/2; give a smaller center or a wider gap",
                    error_at(model_->parameters[static_cast<std::size_t>(n.param[1])].where), model_->name, path, center, 0.5 * width));
  }
}

Network Network::with_parameters(const std::vector<double>& values) const {
  if (values.size() != parameters_.size())
    throw std::logic_error(fmt::format("model '{}' has {} parameters, {} values given", model_->name, parameters_.size(), values.size()));
  Network copy = *this;
  // Parameters are stored in dependency order by the checker only for literals; evaluate
  // derived ones repeatedly until stable (chains are short and acyclic).
  copy.parameters_ = values;
  for (std::size_t pass = 0; pass < copy.parameters_.size() + 1; ++pass) {
    bool changed = false;
    for (std::size_t i = 0; i < model_->parameters.size(); ++i) {
      const auto& expression = model_->parameters[i].expression;
      if (expression.is_constant()) continue;
      const double v = expression.evaluate(copy.parameters_);
      if (v != copy.parameters_[i]) {
        copy.parameters_[i] = v;
        changed = true;
      }
    }
    if (!changed) break;
  }
  copy.derive();
  return copy;
}

std::string Network::describe() const {
  const Topology& t = *topology_;
  std::string out = fmt::format(
      "model {}: {} parameters ({} free), {} elements\n", model_->name, parameters_.size(),
      [&] {
        int n = 0;
        for (const auto& p : model_->parameters) n += p.free ? 1 : 0;
        return n;
      }(),
      t.probes.size());
  out += fmt::format("  nodes: driven terminal, ground, {} internal\n", t.internal_nodes);
  out += fmt::format("  root branches: {} spring, {} yeoh, {} dashpot, {} maxwell, {} friction, {} slider, {} subtree\n", t.springs.size(),
                     t.yeohs.size(), t.dashpots.size(), t.maxwells.size(), t.frictions.size(), t.sliders.size(), t.subtrees.size());
  for (const auto& chain : t.springpots)
    out += fmt::format("  springpot {}: {} Maxwell modes over {:g} .. {:g} Hz\n", chain.path, chain.modes, parameter(chain.param[3]),
                       parameter(chain.param[4]));
  out += fmt::format("  state variables: {}\n", t.state_size);
  out += fmt::format("  linear: {}, force jumps with rate: {}\n", t.is_linear ? "yes" : "no", t.has_rate_jump ? "yes" : "no");
  return out;
}

}  // namespace rheo::runtime
