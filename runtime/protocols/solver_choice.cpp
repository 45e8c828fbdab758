#include "runtime/protocols/solver_choice.hpp"

#include <algorithm>

namespace rheo::runtime {

namespace {

// Blocks on the longest path from `index` down to a leaf (0 for a leaf).
int block_depth(const Topology& t, int index) {
  const TreeNode& node = t.nodes[static_cast<std::size_t>(index)];
  int deepest = 0;
  for (int i = 0; i < node.child_count; ++i)
    deepest = std::max(deepest, block_depth(t, t.children[static_cast<std::size_t>(node.first_child + i)]));
  return node.child_count > 0 ? deepest + 1 : 0;
}

// Whether a bouc_wen lies below `index` with a series block on its way up (between internal nodes).
bool nested_bouc_wen(const Topology& t, int index, bool below_series) {
  const TreeNode& node = t.nodes[static_cast<std::size_t>(index)];
  if (node.kind == NodeKind::bouc_wen) return below_series;
  for (int i = 0; i < node.child_count; ++i)
    if (nested_bouc_wen(t, t.children[static_cast<std::size_t>(node.first_child + i)], below_series || node.kind == NodeKind::series)) return true;
  return false;
}

}  // namespace

bool uses_sundials(const Network& network, SolverChoice choice) {
  if (choice != SolverChoice::automatic) return choice == SolverChoice::sundials;
  const Topology& t = network.topology();
  for (int root : t.subtrees)
    if (nested_bouc_wen(t, root, false)) return false;
  if (has_inerter(network)) return true;
  for (int root : t.subtrees)
    if (block_depth(t, root) > kFixedStepMaxBlockDepth) return true;
  return false;
}

bool has_inerter(const Network& network) {
  for (const auto& node : network.topology().nodes)
    if (node.kind == NodeKind::inerter) return true;
  return false;
}

}  // namespace rheo::runtime
