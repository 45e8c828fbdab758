#include "runtime/closed_form/pwl_branch.hpp"

#include "runtime/network/leaf_kernels.hpp"

#include <array>
#include <numeric>

namespace rheo::runtime {
namespace {

struct BranchBuilder {
  const Network& network;
  PwlBranch& branch;

  double parameter(const TreeNode& node, int slot) const { return network.parameter(node.param[slot]); }
  int new_node() { return branch.internal_nodes++; }
  void add(PwlEdgeKind kind, int a, int b, double value, double cap_neg = 0.0, double center = 0.0) {
    if (kind == PwlEdgeKind::slider || kind == PwlEdgeKind::gap) branch.switches.push_back(static_cast<int>(branch.edges.size()));
    branch.edges.push_back({kind, a, b, value, cap_neg, center});
  }
  // A slider of caps in slots (pos, neg) of NODE: separate slots make the branch uneven.
  void add_slider(const TreeNode& node, int pos, int neg, int a, int b) {
    if (node.param[neg] != node.param[pos]) branch.odd = false;
    add(PwlEdgeKind::slider, a, b, parameter(node, pos), parameter(node, neg));
  }

  // False when the subtree holds an element that is not piecewise linear.
  bool place(int index, int a, int b) {
    const Topology& t = network.topology();
    const TreeNode& node = t.nodes[static_cast<std::size_t>(index)];
    switch (node.kind) {
      case NodeKind::spring: add(PwlEdgeKind::spring, a, b, parameter(node, 0)); return true;
      case NodeKind::dashpot: add(PwlEdgeKind::dashpot, a, b, parameter(node, 0)); return true;
      case NodeKind::inerter: add(PwlEdgeKind::inerter, a, b, parameter(node, 0)); return true;
      case NodeKind::slider: add_slider(node, 0, 1, a, b); return true;
      case NodeKind::gap:
        if (parameter(node, 1) != 0.0 || network.model().parameters[static_cast<std::size_t>(node.param[1])].free) branch.odd = false;
        add(PwlEdgeKind::gap, a, b, 0.5 * parameter(node, 0), 0.0, gap_center(parameter(node, 0), parameter(node, 1)));  // as the kernels
        return true;
      case NodeKind::maxwell: {
        const int mid = new_node();
        add(PwlEdgeKind::spring, a, mid, parameter(node, 0));
        add(PwlEdgeKind::dashpot, mid, b, parameter(node, 1));
        return true;
      }
      case NodeKind::friction: {
        const int mid = new_node();
        add(PwlEdgeKind::spring, a, mid, parameter(node, 0));
        add_slider(node, 1, 2, mid, b);
        return true;
      }
      case NodeKind::parallel:
        for (int c = 0; c < node.child_count; ++c)
          if (!place(t.children[static_cast<std::size_t>(node.first_child + c)], a, b)) return false;
        return true;
      case NodeKind::series: {
        int from = a;
        for (int c = 0; c < node.child_count; ++c) {
          const int to = c + 1 == node.child_count ? b : new_node();
          if (!place(t.children[static_cast<std::size_t>(node.first_child + c)], from, to)) return false;
          from = to;
        }
        return true;
      }
      case NodeKind::yeoh:
      case NodeKind::poly_spring:
      case NodeKind::quadratic_dashpot:
      case NodeKind::bouc_wen: return false;
    }
    return false;
  }
};

// Whether the sliders and gaps, all rigid at once, form a forest on the graph in which the
// terminal and ground are one node (both have prescribed positions): then in every mode the
// rigid edges' constraints are independent and their forces determined.
// BRANCH has at most kPwlMaxDim / 2 internal nodes (PwlBranch::build checks that first).
bool switches_form_forest(const PwlBranch& branch) {
  const int known = branch.internal_nodes;  // terminal and ground
  std::array<int, kPwlMaxDim / 2 + 1> parent{};
  std::iota(parent.begin(), parent.begin() + known + 1, 0);
  auto find = [&](int x) {
    while (parent[static_cast<std::size_t>(x)] != x)
      x = parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
    return x;
  };
  auto slot = [&](int node) { return node < 0 ? known : node; };
  for (int s : branch.switches) {
    const PwlEdge& e = branch.edges[static_cast<std::size_t>(s)];
    const int ra = find(slot(e.a)), rb = find(slot(e.b));
    if (ra == rb) return false;
    parent[static_cast<std::size_t>(ra)] = rb;
  }
  return true;
}

}  // namespace

bool PwlBranch::build(const Network& network, int root, PwlBranch& out) {
  // Emptied in place: a branch is built per harmonic point, its storage kept (no allocation).
  out.internal_nodes = 0, out.odd = true;
  out.edges.clear(), out.switches.clear();
  BranchBuilder builder{network, out};
  if (!builder.place(root, kPwlTerminal, kPwlGround)) return false;
  const int switches = static_cast<int>(out.switches.size());
  if (2 * out.internal_nodes + switches + 3 > kPwlMaxDim || 2 * switches > kPwlMaxDim) return false;
  return switches > 0 && switches_form_forest(out);
}

}  // namespace rheo::runtime
