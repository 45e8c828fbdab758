// Settling to a periodic state by cycles, accelerated where it is geometric. A slow mode (a
// Maxwell element with tau >> the period, a springpot's tail) moves a state's end-of-cycle value
// by d_n = s_n - s_{n-1} with d_{n+1} = rho d_n, so its periodic value is
//   s_inf = s_n + d_n rho / (1 - rho):
// the skip jumps there. It is only a better start: convergence is still declared on the change
// over simulated cycles, and a poor skip costs cycles, not accuracy. Fixed steps skip subtree by
// subtree (protocols/cycle_groups.hpp), IDA component by component (ComponentSettling below).
#pragma once

#include <cstddef>
#include <vector>

namespace rheo::runtime {

// Whether a change contracts at a steady geometric rate: the last two rates lie in
// [0.3, 1 - 1e-7] (faster, a few cycles finish anyway) and agree within 5 % of the smaller of rho
// and 1 - rho. The skip multiplies the last change by rho/(1 - rho) (up to 1e7), so an error
// d rho in rho errs by d rho/(1 - rho) of the remaining distance: at most 5 % of it, which the
// next skips remove (a gap's play shared with a bouc_wen's set, rho = 0.9993:
// tests/corpus/repro/backends/03). (5 % of rho alone, as up to 0.999 before, let rates of
// 1.0002 and 0.9989 skip by 880 times a change known to 100 %: a springpot behind friction at
// 20 Hz then never settled.)
bool steady_contraction(double rate, double previous_rate);

// The skip for a state of independent components (IDA's node positions and Bouc-Wen states,
// dae_protocols.cpp), each settling at its own rate: a component moves only where its own last
// three changes contract steadily (its two rates d_n/d_{n-1} and d_{n-1}/d_{n-2}, of one sign,
// pass steady_contraction), its last change is above NOISE times its scale (below it, the
// integrator's own error makes the rates noise) and its remaining distance d_n rho/(1 - rho) is
// above FLOOR times its scale (a mode at rho = 0.994 whose changes had fallen below the floor
// still lay 160 changes from its limit: differential seed 2026, model 0, took 313 cycles). A
// component that oscillates, drifts or settles in another way keeps its value: one component's
// rate is never applied to another's (an undamped mass's drift multiplied by a slow mode's factor
// grew without bound, cycle_groups.hpp).
//
// A skip can lead where the integrator finds no consistent state: differential seed 73, model
// 243, a slider that ratchets (it slips further one way every cycle, in a chain with no static
// stiffness) moved its positions on by nearly the same amount every cycle, at rates of 0.9995
// that pass as a slow contraction, and the skip of 2000 changes (83 mm) stretched its nonlinear
// springs until IDACalcIC failed. The caller then moves back and refuses the skip: its components
// are never moved again. (Whether a skip settled is not judged by the change after it: the
// slow tails of springpots keep up to 0.96 of it on IDA (dae_protocols_test), and behind friction
// on fixed steps change by up to 2.7 times as much in the cycle after a skip that still brings
// them closer, harmonic_test.)
class ComponentSettling {
 public:
  // SCALES: each component's size (e.g. the amplitude for a position) [its unit]; FLOOR and
  // NOISE [-] (NOISE at most FLOOR; by default the same).
  ComponentSettling(std::vector<double> scales, double floor, double noise = 1.0);
  // Records STATE, the value at a cycle's end. Returns true and sets TARGET to STATE with each
  // steadily contracting component moved to its geometric limit, when any is; else false.
  bool record(const std::vector<double>& state, std::vector<double>& target);
  // The state was moved to the last TARGET (or restarted): the next changes are measured from the
  // next record.
  void forget() { kept_ = 0; }
  // The state could not be moved to the last TARGET (the integrator found no state there): none
  // of the components moved there is moved again.
  void refuse_last();
  // Whether a skip was refused.
  bool refused() const;

 private:
  std::vector<double> scales_;
  double floor_;
  double noise_;
  std::vector<double> states_[4];  // the last four records, oldest first
  std::size_t kept_ = 0;
  std::vector<bool> skipped_;  // components the last record moved
  std::vector<bool> refused_;  // components never moved again
};

}  // namespace rheo::runtime
