#include "runtime/stepping/tree_newton_plan.hpp"

#include "runtime/network/leaf_kernels.hpp"

#include <cmath>
#include <limits>

namespace rheo::runtime {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

void NewtonWork::resize(std::size_t nodes) {
  for (auto* v : {&x, &saved, &target, &input, &out, &hat, &tangent, &load, &slope, &last, &last_de}) v->assign(nodes, 0.0);
  state.assign(nodes, 0);
}

void NewtonLayout::prepare(const Network& network, const std::vector<Interval>& bounds, const std::vector<double>& coefficient) {
  const Topology& t = network.topology();
  const std::size_t count = t.nodes.size();
  role.assign(count, NewtonRole::closed);
  domain.assign(count, Interval{-kInf, kInf});
  reaches_hi.assign(count, 0);
  reaches_lo.assign(count, 0);
  saturates_hi.assign(count, 0);
  saturates_lo.assign(count, 0);
  stiffness.assign(count, 0.0);
  extent.assign(count, 1);
  pivot.assign(count, 0);
  kinked.assign(count, 0);
  iterative.assign(count, 0);
  auto child = [&](const TreeNode& n, int i) { return static_cast<std::size_t>(t.children[static_cast<std::size_t>(n.first_child + i)]); };
  for (std::size_t i = count; i-- > 0;) {  // children follow their parent
    const TreeNode& n = t.nodes[i];
    auto p = [&](int slot) { return network.parameter(n.param[slot]); };
    switch (n.kind) {
      case NodeKind::friction:
      case NodeKind::slider:
        reaches_hi[i] = reaches_lo[i] = 1;
        if (n.kind == NodeKind::friction) stiffness[i] = p(0);
        break;
      case NodeKind::spring:
      case NodeKind::maxwell:
      case NodeKind::bouc_wen:
      case NodeKind::poly_spring: stiffness[i] = p(0); break;
      case NodeKind::yeoh: stiffness[i] = 2.0 * p(0); break;
      case NodeKind::dashpot:
      case NodeKind::inerter: stiffness[i] = coefficient[i]; break;
      case NodeKind::parallel:
      case NodeKind::series: {
        const bool series = n.kind == NodeKind::series;
        reaches_hi[i] = reaches_lo[i] = series ? 0 : 1;
        for (int k = 0; k < n.child_count; ++k) {
          const std::size_t c = child(n, k);
          stiffness[i] += stiffness[c];
          extent[i] += extent[c];
          if (series) {  // reached if the member that bounds the chain reaches its bound
            reaches_hi[i] |= static_cast<std::uint8_t>(reaches_hi[c] && bounds[c].hi == bounds[i].hi);
            reaches_lo[i] |= static_cast<std::uint8_t>(reaches_lo[c] && bounds[c].lo == bounds[i].lo);
          } else {  // a sum of caps is reached when every one is
            reaches_hi[i] &= reaches_hi[c];
            reaches_lo[i] &= reaches_lo[c];
          }
        }
        break;
      }
      default: break;  // gap, quadratic_dashpot: no stiffness of their own
    }
  }
  for (double& k : stiffness)
    if (!(k > 0.0)) k = 1.0;  // N/mm: only where nothing below has a stiffness (gaps, quadratic dashpots)
  // Roles from each subtree root down; `forward`: the parent is a parallel block (or none).
  auto visit = [&](auto& self, std::size_t i, bool forward) -> bool {
    const TreeNode& n = t.nodes[i];
    // In a chain, bouc_wen, yeoh and poly_spring are stepped forward from their own elongation
    // increment (their inverses are solves: a march and a root, a cubic or quintic root).
    const bool law = n.kind == NodeKind::bouc_wen || n.kind == NodeKind::yeoh || n.kind == NodeKind::poly_spring;
    if (law && !forward) {
      role[i] = NewtonRole::member;
      pivot[i] = 1;
      kinked[i] = static_cast<std::uint8_t>(n.kind == NodeKind::bouc_wen);
      return true;
    }
    if (n.child_count == 0 || n.linear) return false;
    if (n.kind == NodeKind::series) {
      if (!forward || n.capped_linear || n.rigid_when_stuck) return false;
      role[i] = NewtonRole::chain;
      Interval d = bounds[i];
      bool peak_hi = false, peak_lo = false;
      for (int k = 0; k < n.child_count; ++k) {
        const std::size_t c = child(n, k);
        self(self, c, false);
        const TreeNode& m = t.nodes[c];
        double hi = kInf, lo = -kInf;  // the peaks of softening springs: open ends
        if (m.kind == NodeKind::yeoh) hi = coefficient[c], lo = -coefficient[c];
        if (m.kind == NodeKind::poly_spring) {
          const PolyLaw poly{network.parameter(m.param[0]), network.parameter(m.param[1]), network.parameter(m.param[2])};
          const PolyLaw::Range r = poly.monotone_range();
          if (std::isfinite(r.hi)) hi = poly.force(r.hi);
          if (std::isfinite(r.lo)) lo = poly.force(r.lo);
        }
        if (hi <= d.hi) d.hi = hi, reaches_hi[i] = 0, peak_hi = true;
        if (lo >= d.lo) d.lo = lo, reaches_lo[i] = 0, peak_lo = true;
      }
      domain[i] = d;
      saturates_hi[i] = static_cast<std::uint8_t>(std::isfinite(d.hi) && !reaches_hi[i] && !peak_hi);
      saturates_lo[i] = static_cast<std::uint8_t>(std::isfinite(d.lo) && !reaches_lo[i] && !peak_lo);
      for (int k = 0; k < n.child_count; ++k)
        kinked[i] |= static_cast<std::uint8_t>(t.nodes[child(n, k)].kind == NodeKind::gap ||
                                               t.nodes[child(n, k)].kind == NodeKind::quadratic_dashpot);
      return true;
    }
    role[i] = forward ? NewtonRole::sum : NewtonRole::block;
    bool unknown = !forward;
    pivot[i] = static_cast<std::uint8_t>(!forward);
    for (int k = 0; k < n.child_count; ++k) {
      const std::size_t c = child(n, k);
      unknown |= self(self, c, true);
      kinked[i] |= static_cast<std::uint8_t>(t.nodes[c].kind == NodeKind::friction || t.nodes[c].kind == NodeKind::bouc_wen);
    }
    return unknown;
  };
  for (int root : t.subtrees) {
    const auto r = static_cast<std::size_t>(root);
    iterative[r] = static_cast<std::uint8_t>(visit(visit, r, true));
  }
}

}  // namespace rheo::runtime
