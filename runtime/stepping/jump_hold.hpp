// A step whose drive ramps by J over its first delta and then holds for the rest (dt - delta):
// what an FMU takes for a held input that jumps into a subtree (runtime/fmu/cosimulation.hpp).
// It is, to rounding, the two kernel steps
//   Simulator::step(StepPlan(delta), ramp by J)   then   Simulator::step(StepPlan(dt - delta), hold),
// taken in one pass where every subtree's step is piecewise affine:
//   - the root block: a Maxwell arm F <- a_r (a_d F + b_d J) is one step with a = a_r a_d,
//     b = a_r b_d (a_d, b_d of the ramp, a_r of the hold); a dashpot carries c 0/(dt - delta) = 0
//     at the end; springs, Yeoh springs, friction elements and sliders end where one step of
//     J leaves them (a return mapping repeated at zero increment changes nothing);
//   - a subtree whose root is linear (springs, dashpots, Maxwell elements, inerters not driven
//     directly) or a capped-linear chain (tree_solver.hpp: linear members, friction elements and
//     sliders) maps its slots x before to its slots after as
//       x+ = E x + M_(m1,m2) [x_live, J, 1],
//     E keeping each elongation (e+ = e + de), x_live the slots the step reads (springs'
//     elongations, Maxwell, friction and inerter forces, inerter velocities), m1 and m2 the
//     chain's mode in each part (free, or slipping at its upper or lower cap). Each part's mode
//     follows from its trial force, itself affine: t1 = g [x_live, J, 1] against the cap, then
//     t2 = g_m1 [x_live, J, 1]. The maps are the two kernel steps themselves, read off column
//     by column on unit states with the chain's cap forced to the mode (the solves are affine
//     within a mode), once per step length. Across a mode boundary the map is continuous (at
//     t = cap the free chain's members take the cap's elongations), so a mode chosen from a
//     trial force within rounding of the cap changes the result by rounding only.
// Subtrees of any other kind (iterated chains, nested caps, Yeoh, bouc_wen, gaps, inerters in
// the root block) are not piecewise affine this way: applies() is false and a caller takes the
// two kernel steps.
#pragma once

#include "runtime/network/network.hpp"
#include "runtime/stepping/simulator.hpp"

#include <array>
#include <vector>

namespace rheo::runtime {

class JumpHoldStep {
 public:
  // Whether every subtree of TOPOLOGY is linear or a capped-linear chain of linear members,
  // friction elements and sliders, with no inerter whose elongation is the drive.
  static bool applies(const Topology& topology);

  // The maps for steps of length DT [s] whose ramp takes the first DELTA [s] (0 < delta < dt),
  // with NETWORK's parameters (NETWORK must outlive this). std::logic_error where !applies.
  JumpHoldStep(const Network& network, double dt, double delta);

  double dt() const { return root_.dt; }
  // Advances BEFORE by the ramp to U_NEXT over delta then the hold; writes AFTER (sized as
  // BEFORE); returns the total force [N] at the end. No allocation.
  double step(const Simulator& simulator, const State& before, double u_next, State& after) const;

 private:
  enum Mode { free = 0, upper = 1, lower = 2 };
  struct Subtree {
    int first = 0, count = 0;                        // its state slots [first, first + count)
    int force_slot = 0;                              // the root node's F
    double cap_lo = 0.0, cap_hi = 0.0;               // the root chain's caps [N] (infinite: linear)
    std::vector<int> live;                           // the slots the step reads
    std::vector<double> elongation;                  // per slot of the range: 1 where it carries over, else 0
    std::vector<double> trial;                       // g: (live + 2) coefficients
    std::array<std::vector<double>, 3> trial_after;  // g_m1
    std::array<std::vector<double>, 9> map;          // M_(m1,m2): count rows of (live + 2), 3 m1 + m2
  };
  Subtree make_subtree(const Network& network, int root, double dt, double delta) const;
  double advance(const Subtree& s, const double* before, double jump, double* after) const;

  StepPlan root_;  // the root block's composed coefficients (its tree plan unused)
  std::vector<Subtree> subtrees_;
  mutable std::vector<double> inputs_;  // scratch [x_live, J, 1]: a step serves one thread at a time
};

}  // namespace rheo::runtime
