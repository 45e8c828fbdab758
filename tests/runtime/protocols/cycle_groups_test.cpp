// The settling of a time-stepped harmonic point group by group: which states form a group, and a
// skip that moves only the groups that contract, each to its own geometric limit (hand values).
// Which rate pairs count as a steady contraction: tests/runtime/core/geometric_settling_test.cpp.
#include "runtime/protocols/cycle_groups.hpp"

#include "support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <vector>

namespace cycle_groups_test {

using namespace rheo;

// Each state slot's group: 0 for the root's own, g + 1 for those of subtree g.
std::vector<int> groups_of_slots(const runtime::Topology& t) {
  std::vector<int> group_of(static_cast<std::size_t>(t.state_size), 0);
  for (std::size_t g = 0; g < t.subtrees.size(); ++g) {
    std::vector<int> pending{t.subtrees[g]};
    while (!pending.empty()) {
      const auto& node = t.nodes[static_cast<std::size_t>(pending.back())];
      pending.pop_back();
      for (int s = 0; s < node.slots; ++s) group_of[static_cast<std::size_t>(node.state + s)] = static_cast<int>(g) + 1;
      for (int c = 0; c < node.child_count; ++c) pending.push_back(t.children[static_cast<std::size_t>(node.first_child + c)]);
    }
  }
  return group_of;
}

TEST_CASE("cycle groups: the root's states and each subtree's, and a skip moves only a group that contracts, by its own rate") {
  const auto network = test::network_from(
      "model m { maxwell (k = 5 N/mm, tau = 10 ms)\n series { spring (k = 1 N/mm)\n maxwell (k = 2 N/mm, tau = 1 s) }\n"
      " series { spring (k = 3 N/mm)\n inerter (b = 1 kg) } }",
      "m");
  const auto& t = network.topology();
  REQUIRE(t.subtrees.size() == 2);
  runtime::CycleGroups groups(t);
  CHECK(groups.groups() == 3);
  // Slots of each group: the root's maxwell force, then the two subtrees' nodes.
  const std::vector<int> group_of = groups_of_slots(t);
  const runtime::CycleScales scales{1.0, 1.0, 1.0, 1.0};
  // Cycle changes per group: the first subtree contracts by 0.5 a cycle, the second swings
  // (+1e-3, -1e-3, ...), the root does not move.
  std::vector<double> start(static_cast<std::size_t>(t.state_size), 0.0), end = start;
  const auto cycle = [&](int n) {
    start = end;
    for (std::size_t i = 0; i < end.size(); ++i) {
      const double slot = static_cast<double>(i + 1);
      if (group_of[i] == 1) end[i] += 0.8 * slot * (n == 0 ? 1.0 : n == 1 ? 0.5 : 0.25);
      if (group_of[i] == 2) end[i] += (n % 2 == 0 ? 1e-3 : -1e-3) * slot;
    }
    return groups.measure(start, end, scales);
  };
  double largest = 0.0;  // the first subtree's last slot moves most
  for (std::size_t i = 0; i < group_of.size(); ++i)
    if (group_of[i] == 1) largest = 0.8 * static_cast<double>(i + 1);
  CHECK(cycle(0) == doctest::Approx(largest));
  cycle(1);
  std::vector<double> state = end;
  CHECK_FALSE(groups.skip_contracting(start, state));  // one rate of 0.5 only
  cycle(2);
  state = end;
  REQUIRE(groups.skip_contracting(start, state));
  for (std::size_t i = 0; i < state.size(); ++i) {
    CAPTURE(i);
    // Group 1 jumps to its limit: the last change 0.2 (i + 1) times rho/(1 - rho) = 1 more.
    if (group_of[i] == 1) CHECK(state[i] == doctest::Approx(end[i] + 0.8 * 0.25 * static_cast<double>(i + 1)));
    else CHECK(state[i] == end[i]);
  }
}

// A complex mode (reproducer 15's ringing inerter mode on coarse fixed steps) keeps the size ratio
// of its changes while they turn: extrapolated along the last change it grew at every skip. Two
// subtrees whose largest changes both fall by 0.66 a cycle: in the first every slot's change is
// 0.66 times its last (a real mode), in the second the smaller slots' changes flip sign every
// cycle (a turning one).
TEST_CASE("cycle groups: a group whose change turns from cycle to cycle is not skipped, one along its last change is") {
  const char* subtree = "series { spring (k = 1 N/mm)\n maxwell (k = 2 N/mm, tau = 1 s)\n maxwell (k = 3 N/mm, tau = 2 s) }";
  const auto network = test::network_from(fmt::format("model m {{ {}\n {} }}", subtree, subtree), "m");
  const auto& t = network.topology();
  REQUIRE(t.subtrees.size() == 2);
  const std::vector<int> group_of = groups_of_slots(t);
  int first_of_group[3] = {-1, -1, -1}, slots_of_group[3] = {0, 0, 0};
  for (std::size_t i = 0; i < group_of.size(); ++i) {
    const auto g = static_cast<std::size_t>(group_of[i]);
    if (first_of_group[g] < 0) first_of_group[g] = static_cast<int>(i);
    ++slots_of_group[g];
  }
  REQUIRE(slots_of_group[1] >= 2);
  REQUIRE(slots_of_group[2] >= 2);
  runtime::CycleGroups groups(t);
  const runtime::CycleScales scales{1.0, 1.0, 1.0, 1.0};
  std::vector<double> start(group_of.size(), 0.0), end = start, state;
  double size = 1.0;
  for (int n = 0; n < 3; ++n, size *= 0.66) {
    start = end;
    for (std::size_t i = 0; i < end.size(); ++i) {
      const auto g = static_cast<std::size_t>(group_of[i]);
      const bool largest = static_cast<int>(i) == first_of_group[g];
      if (g == 1) end[i] += size * (largest ? 1.0 : 0.5);
      if (g == 2) end[i] += size * (largest ? 1.0 : (n % 2 == 0 ? 0.5 : -0.5));
    }
    groups.measure(start, end, scales);
  }
  state = end;
  REQUIRE(groups.skip_contracting(start, state));
  for (std::size_t i = 0; i < state.size(); ++i) {
    CAPTURE(i);
    if (group_of[i] == 1) CHECK(state[i] == doctest::Approx(end[i] + (end[i] - start[i]) * 0.66 / 0.34));
    else CHECK(state[i] == end[i]);
  }
}

}  // namespace cycle_groups_test
