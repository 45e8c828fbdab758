// The compiled network: an immutable state-space graph built once from a checked model.
//
// Structure is immutable and shared; only a State (simulator.hpp) changes while simulating.
// Displacement-driven: the terminal node follows the drive u(t), the other terminal is ground.
//
// Compilation canonicalises the element tree:
//  - blocks with one child are replaced by the child; parallel-in-parallel and
//    series-in-series are spliced;
//  - a series chain holding exactly one spring and one dashpot fuses them into a Maxwell
//    member, so that it gets the exact exponential update (eq. 2.7) rather than an implicit one;
//  - a springpot becomes a parallel block of Maxwell elements (runtime/network/springpot.hpp) whose
//    stiffnesses and dampings are derived parameters, recomputed whenever parameters change;
//    the block is never spliced into an enclosing block except the root, whose Maxwell group
//    takes its modes (so a springpot beside the thesis elements keeps the closed form);
//  - leaves directly in the root parallel block are grouped by kind into flat arrays
//    (the hot loop of the thesis models); everything else, and every inerter,
//    quadratic_dashpot, gap, bouc_wen and poly_spring leaf, and every friction element or slider
//    with one-sided yield forces (fy_pos != fy_neg as written), even in the root block (a
//    one-node subtree), is a subtree solved by TreeSolver.
// Internal nodes are the junctions inside series chains: a chain of m members has m-1.
//
// Placement rules (ModelError naming the element, with advice, otherwise):
//  - a gap is a direct member of a series chain with at least one compliant member, and its
//    rest position lies in its play: |center| <= width/2 as written;
//  - an inerter below the root block has a compliant member in series with it (in some
//    enclosing chain), so that it is never rigidly driven: a velocity jump of the drive would
//    be an impact (an unbounded force), and the implicit inerter relation is unstable as a
//    differentiator. In the root block it is driven directly (drive_prescribed below).
// Compliant: spring, yeoh, poly_spring, dashpot, maxwell, friction, bouc_wen or quadratic_dashpot; a
// parallel block of compliant members; a series chain with a compliant member. Not compliant:
// slider, gap, inerter (rigid while stuck, in contact, or to a velocity jump).
#pragma once

#include "lang/model.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace rheo::runtime {

enum class NodeKind : std::uint8_t {
  spring,
  yeoh,
  dashpot,
  maxwell,
  friction,
  slider,
  inerter,
  quadratic_dashpot,
  gap,
  bouc_wen,
  poly_spring,
  parallel,
  series
};

// A node of a subtree below the root. Leaves carry parameter indices (the slots of
// lang/model.hpp, except that a friction element's param[2] and a slider's param[1] always
// name the compression yield force fy_neg: the fy slot again when it was given symmetric);
// blocks carry children.
// Every subtree node owns `slots` consecutive state slots at `state`: elongation e [mm] and
// force F [N] at the last step, then
//   inerter (Newmark):           v [mm/s], the velocity at the last step;
//   inerter (drive_prescribed):  r0, r1 [mm/s], the mean rates of the last two steps, and
//                                h0, h1 [s], their lengths (0: at rest before the drive began).
struct TreeNode {
  NodeKind kind = NodeKind::parallel;
  int first_child = 0;  // into Topology::children
  int child_count = 0;
  int param[3] = {-1, -1, -1};
  int state = -1;  // offset of (e, F, ...) in State::values
  int slots = 2;
  bool rigid_when_stuck = false;  // force is set-valued at zero elongation rate (sliders)
  bool drive_prescribed = false;  // an inerter in the root block: its elongation is the drive
  bool linear = false;            // only springs, dashpots, Maxwell elements and inerters below
  // A series chain of linear members, friction elements and sliders (not all sliders): its
  // step relation is F = clamp(F0 + S de, cap), solved without iteration (tree_solver.hpp).
  bool capped_linear = false;
};

// What a state slot holds, for scaling its change (harmonic steady-state detection).
enum class StateScale : std::uint8_t { force, length, velocity, time };

// Where the force and elongation of an element the user wrote are read from.
struct ElementProbe {
  std::string path;
  lang::ElementKind kind;
  enum class Source : std::uint8_t {
    root_spring,
    root_yeoh,
    root_dashpot,
    root_maxwell,
    root_friction,
    root_slider,
    root_springpot,        // `count` consecutive root Maxwell elements from `index`
    tree_node,             // a subtree node: its (e, F) slots
    tree_maxwell_spring,   // the spring of a fused spring+dashpot pair: e = F/k
    tree_maxwell_dashpot,  // the dashpot of a fused pair: e = e_pair - F/k
  } source;
  int index = 0;  // into the root group or Topology::nodes
  int count = 1;
};

// A springpot's Maxwell chain. Its mode stiffnesses k_j [N/mm] are the network parameters
// first_derived + j and its dampings c_j [N*s/mm] first_derived + modes + j, j < modes
// (derived parameters are indexed after the model's own).
struct SpringpotChain {
  std::string path;
  int param[5];  // k, alpha, tau, f_low, f_high: model parameter indices
  int first_derived = 0;
  int modes = 0;
};

struct Topology {
  // Root parallel block, grouped by kind; entries are parameter indices.
  std::vector<int> springs;                   // k
  std::vector<std::array<int, 3>> yeohs;      // D10, D20, D30
  std::vector<int> dashpots;                  // c
  std::vector<std::array<int, 2>> maxwells;   // k, c
  std::vector<std::array<int, 2>> frictions;  // k, fy
  std::vector<int> sliders;                   // fy
  std::vector<int> subtrees;                  // node indices of subtree roots

  std::vector<TreeNode> nodes;
  std::vector<int> children;
  std::vector<ElementProbe> probes;  // one per element the user wrote, in source order
  std::vector<SpringpotChain> springpots;
  int derived_parameters = 0;  // springpot modes, indexed after the model's parameters

  int internal_nodes = 0;                // junctions inside series chains
  int state_size = 0;                    // maxwell F, friction F, slider F, then TreeNode::slots per tree node
  std::vector<StateScale> state_scales;  // one per slot
  int maxwell_state() const { return 0; }
  int friction_state() const { return static_cast<int>(maxwells.size()); }
  int slider_state() const { return friction_state() + static_cast<int>(frictions.size()); }

  // The force can jump with the drive rate: a dashpot or quadratic_dashpot with nothing in
  // series but members rigid to a rate jump (sliders, gaps, inerters).
  bool has_rate_jump = false;
  bool is_linear = false;  // only springs, dashpots, Maxwell elements and inerters
};

// Numbers derived from parameter values, laid out per root group (flat arrays for the kernels).
struct Coefficients {
  double spring_k = 0.0;   // sum of root spring stiffnesses [N/mm]
  double dashpot_c = 0.0;  // sum of root dashpot coefficients [N*s/mm]
  std::vector<double> yeoh_d10, yeoh_d20, yeoh_d30;
  std::vector<double> maxwell_k, maxwell_c;
  std::vector<double> friction_k, friction_fy;
  std::vector<double> slider_fy;
  double slider_fy_total = 0.0;
};

class Network {
 public:
  // Compiles a checked model. Throws ModelError with advice for networks that
  // cannot be driven (e.g. a yeoh spring whose force law is not monotone over the range used
  // is diagnosed at run time, not here).
  static Network compile(const lang::CheckedModel& model);

  // The same structure with new values for all parameters (internal units); derived
  // parameters are re-evaluated from their expressions. Used by fitting. One value per model
  // parameter (std::logic_error otherwise); ModelError when the values put a springpot's f_low
  // at or above its f_high (bounds that overlap).
  Network with_parameters(const std::vector<double>& values) const;

  const lang::CheckedModel& model() const { return *model_; }
  const Topology& topology() const { return *topology_; }
  const Coefficients& coefficients() const { return coefficients_; }
  // The model's parameters (internal units), in CheckedModel::parameters order.
  const std::vector<double>& parameters() const { return parameters_; }
  // A model parameter, or (index >= parameters().size()) a derived one (springpot modes).
  double parameter(int index) const {
    const auto i = static_cast<std::size_t>(index);
    return i < parameters_.size() ? parameters_[i] : derived_[i - parameters_.size()];
  }

  // A readable description of the compiled graph, for `rheo check --graph`.
  std::string describe() const;

 private:
  std::shared_ptr<const lang::CheckedModel> model_;
  std::shared_ptr<const Topology> topology_;
  std::vector<double> parameters_;
  std::vector<double> derived_;
  Coefficients coefficients_;

  // Recomputes derived_ and coefficients_ from parameters_.
  void derive();
  // ModelError for a gap whose written rest position is outside its play (|center| > width/2);
  // fitted values beyond act as +-width/2 (leaf_kernels.hpp gap_center).
  void check_gap_centres() const;
};

}  // namespace rheo::runtime
