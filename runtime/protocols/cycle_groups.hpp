// The cycle-to-cycle settling of a time-stepped harmonic point, measured and accelerated group by
// group of states that move independently.
//
// Under a prescribed drive the root's parallel members do not act on each other: each subtree,
// and the root's own Maxwell, friction and slider states, settle at their own rates. A slow mode
// (a Maxwell element with tau >> period in a subtree that starts at rest) moves its group's
// end-of-cycle state by d_n = s_n - s_{n-1} with d_{n+1} = rho d_n, so the group's periodic
// state is s_n + d_n rho/(1 - rho): the skip jumps there. It is only a better start; convergence
// is still declared on the change over simulated cycles, and a poor skip costs cycles, not
// accuracy. Each group skips on its own rate, and a group that does not contract is left where it
// is: multiplied by rho/(1 - rho) of another group's rate at every skip, an undamped mass's drift
// on a branch of its own grew into an oscillation without bound (a springpot behind friction
// beside a mass on a spring).
#pragma once

#include "runtime/network/network.hpp"

#include <vector>

namespace rheo::runtime {

// Scales of the state variables of a cycle: forces by F^ [N], elongations by u0 [mm],
// velocities by w u0 [mm/s], times by the period [s].
struct CycleScales {
  double force, length, velocity, time;
  double of(StateScale kind) const;
};

// Whether a change contracts at a steady geometric rate: the last two rates lie in
// [0.3, 1 - 1e-7] (faster, a few cycles finish anyway) and agree within 5 % of the smaller of rho
// and 1 - rho. The skip multiplies the last change by rho/(1 - rho) (up to 1e7), so an error
// d rho in rho errs by d rho/(1 - rho) of the remaining distance: at most 5 % of it, which the
// next skips remove (a gap's play shared with a bouc_wen's set, rho = 0.9993:
// tests/corpus/repro/backends/03). (5 % of rho alone, as up to 0.999 before, let rates of
// 1.0002 and 0.9989 skip by 880 times a change known to 100 %: a springpot behind friction at
// 20 Hz then never settled.)
bool steady_contraction(double rate, double previous_rate);

class CycleGroups {
 public:
  // Groups: the root's own states, then one per subtree (Topology::subtrees).
  explicit CycleGroups(const Topology& topology);

  // The largest change of any state over the cycle from START to END, relative to its scale;
  // each group's own largest change and its rate against the last cycle's are kept.
  double measure(const std::vector<double>& start, const std::vector<double>& end, const CycleScales& scales);
  // Moves every group whose change contracts steadily (its rates of the last two cycles) to its
  // geometric limit from the cycle that started at CYCLE_START; true if any moved.
  bool skip_contracting(const std::vector<double>& cycle_start, std::vector<double>& state) const;

  int groups() const { return static_cast<int>(change_.size()); }

 private:
  const Topology& topology_;
  std::vector<int> group_of_slot_;
  std::vector<double> change_, previous_change_, rate_, previous_rate_;
};

}  // namespace rheo::runtime
