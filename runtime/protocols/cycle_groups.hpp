// The cycle-to-cycle settling of a time-stepped harmonic point, measured and accelerated group by
// group of states that move independently (the skip's rule: runtime/core/geometric_settling.hpp).
//
// Under a prescribed drive the root's parallel members do not act on each other: each subtree,
// and the root's own Maxwell, friction and slider states, settle at their own rates (a Maxwell
// element with tau >> period in a subtree that starts at rest). Each group skips to its geometric
// limit on its own rate, and a group that does not contract is left where it is: multiplied by rho/(1 - rho) of another group's rate at every skip, an undamped mass's drift
// on a branch of its own grew into an oscillation without bound (a springpot behind friction
// beside a mass on a spring).
#pragma once

#include "runtime/core/geometric_settling.hpp"
#include "runtime/network/network.hpp"

#include <vector>

namespace rheo::runtime {

// Scales of the state variables of a cycle: forces by F^ [N], elongations by u0 [mm],
// velocities by w u0 [mm/s], times by the period [s].
struct CycleScales {
  double force, length, velocity, time;
  double of(StateScale kind) const;
};

// steady_contraction: runtime/core/geometric_settling.hpp.

class CycleGroups {
 public:
  // Groups: the root's own states, then one per subtree (Topology::subtrees).
  explicit CycleGroups(const Topology& topology);

  // The largest change of any state over the cycle from START to END, relative to its scale;
  // each group's own largest change and its rate against the last cycle's are kept.
  double measure(const std::vector<double>& start, const std::vector<double>& end, const CycleScales& scales);
  // Moves every group whose change contracts steadily (its rates of the last two cycles), and
  // along its last change (along_last_change), to its geometric limit from the cycle that started
  // at CYCLE_START; true if any moved.
  bool skip_contracting(const std::vector<double>& cycle_start, std::vector<double>& state) const;

  int groups() const { return static_cast<int>(change_.size()); }

 private:
  // Whether group G's last change is its change before times its rate, slot by slot, within
  // kAlongLastChange of its size: the skip extrapolates along the last change, which holds for a
  // real geometric mode. A complex one (a ringing mode, z = r e^{i phi} a cycle) keeps its size
  // ratio r from cycle to cycle while its change turns: extrapolated by r/(1 - r) along the last
  // change, it grew 3.9 times in the cycle after each skip (reproducer 15: Newmark's inerter
  // mode at 128 steps a cycle, r = 0.66, the change 1.7 times larger every three cycles, so the
  // point never settled).
  bool along_last_change(std::size_t g) const;
  static constexpr double kAlongLastChange = 0.1;

  const Topology& topology_;
  std::vector<int> group_of_slot_;
  std::vector<double> change_, previous_change_, rate_, previous_rate_;
  std::vector<double> slot_change_, previous_slot_change_;  // each slot's change over the last cycle and the one before, by its scale
};

}  // namespace rheo::runtime
