#include "runtime/protocols/cycle_groups.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rheo::runtime {

double CycleScales::of(StateScale kind) const {
  switch (kind) {
    case StateScale::force: return force;
    case StateScale::length: return length;
    case StateScale::velocity: return velocity;
    case StateScale::time: return time;
  }
  return force;
}

namespace {

void mark(const Topology& t, int node, int group, std::vector<int>& group_of_slot) {
  const TreeNode& n = t.nodes[static_cast<std::size_t>(node)];
  for (int s = 0; s < n.slots; ++s) group_of_slot[static_cast<std::size_t>(n.state + s)] = group;
  for (int c = 0; c < n.child_count; ++c) mark(t, t.children[static_cast<std::size_t>(n.first_child + c)], group, group_of_slot);
}

}  // namespace

CycleGroups::CycleGroups(const Topology& topology) : topology_(topology), group_of_slot_(static_cast<std::size_t>(topology.state_size), 0) {
  for (std::size_t g = 0; g < topology.subtrees.size(); ++g) mark(topology, topology.subtrees[g], static_cast<int>(g) + 1, group_of_slot_);
  const std::size_t groups = topology.subtrees.size() + 1;
  change_.assign(groups, 0.0);
  previous_change_.assign(groups, std::numeric_limits<double>::infinity());
  rate_.assign(groups, 0.0);
  previous_rate_.assign(groups, 0.0);
}

double CycleGroups::measure(const std::vector<double>& start, const std::vector<double>& end, const CycleScales& scales) {
  previous_change_.swap(change_);
  previous_rate_.swap(rate_);
  previous_slot_change_.swap(slot_change_);
  slot_change_.resize(start.size());
  std::fill(change_.begin(), change_.end(), 0.0);
  double largest = 0.0;
  for (std::size_t i = 0; i < start.size(); ++i) {
    slot_change_[i] = (end[i] - start[i]) / scales.of(topology_.state_scales[i]);
    const double change = std::abs(slot_change_[i]);
    double& group = change_[static_cast<std::size_t>(group_of_slot_[i])];
    group = std::max(group, change);
    largest = std::max(largest, change);
  }
  for (std::size_t g = 0; g < change_.size(); ++g) rate_[g] = change_[g] / previous_change_[g];
  return largest;
}

bool CycleGroups::skip_contracting(const std::vector<double>& cycle_start, std::vector<double>& state) const {
  bool moved = false;
  for (std::size_t g = 0; g < change_.size(); ++g) {
    if (!steady_contraction(rate_[g], previous_rate_[g]) || !along_last_change(g)) continue;
    const double factor = rate_[g] / (1.0 - rate_[g]);
    for (std::size_t i = 0; i < state.size(); ++i)
      if (static_cast<std::size_t>(group_of_slot_[i]) == g) state[i] += factor * (state[i] - cycle_start[i]);
    moved = true;
  }
  return moved;
}

bool CycleGroups::along_last_change(std::size_t g) const {
  if (previous_slot_change_.size() != slot_change_.size()) return false;
  double off = 0.0;
  for (std::size_t i = 0; i < slot_change_.size(); ++i)
    if (static_cast<std::size_t>(group_of_slot_[i]) == g) off = std::max(off, std::abs(slot_change_[i] - rate_[g] * previous_slot_change_[i]));
  return off <= kAlongLastChange * change_[g];
}

}  // namespace rheo::runtime
