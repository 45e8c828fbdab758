#include "runtime/stepping/periodic_start.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

namespace rheo::runtime {
namespace {

using Complex = std::complex<double>;

class LinearisedSubtree {
 public:
  LinearisedSubtree(const Network& network, const TreeStepPlan& plan, Complex z)
      : t_(network.topology()), network_(network), plan_(plan), z_inverse_(1.0 / z) {}

  bool supported(int node) const {
    const TreeNode& n = at(node);
    switch (n.kind) {
      case NodeKind::gap:
      case NodeKind::bouc_wen:
      case NodeKind::quadratic_dashpot: return false;
      case NodeKind::parallel:
      case NodeKind::series:
        if (n.rigid_when_stuck) return false;
        for (int i = 0; i < n.child_count; ++i)
          if (!supported(child(n, i))) return false;
        return true;
      default: return true;
    }
  }

  // Discrete dynamic stiffness [N/mm]; sliders (rigid while stuck) are never asked: their
  // chains skip them, and blocks rigid as a whole are not supported.
  Complex stiffness(int node) const {
    const TreeNode& n = at(node);
    const Complex difference = 1.0 - z_inverse_;
    switch (n.kind) {
      case NodeKind::spring:
      case NodeKind::friction: return p(n, 0);
      case NodeKind::yeoh: return 2.0 * p(n, 0);  // slope at e = 0
      case NodeKind::poly_spring: return p(n, 0);
      case NodeKind::dashpot: return coefficient(node) * difference;
      case NodeKind::maxwell: {
        const MaxwellStep& m = plan_.maxwell[static_cast<std::size_t>(node)];
        return m.b * difference / (1.0 - m.a * z_inverse_);
      }
      case NodeKind::inerter: {
        const Complex tustin = difference / (1.0 + z_inverse_);
        return coefficient(node) * tustin * tustin;
      }
      case NodeKind::parallel: {
        Complex sum = 0.0;
        for (int i = 0; i < n.child_count; ++i) sum += stiffness(child(n, i));
        return sum;
      }
      case NodeKind::series: {
        Complex compliance = 0.0;
        for (int i = 0; i < n.child_count; ++i)
          if (at(child(n, i)).kind != NodeKind::slider) compliance += 1.0 / stiffness(child(n, i));
        return 1.0 / compliance;
      }
      default: return 0.0;
    }
  }

  // Writes the state at k = 0 of `node`, whose elongation and force phasors are e and f.
  // Returns whether every cap holds over the whole cycle (|F| <= fy of each slider and
  // friction element; the smaller of fy_pos and fy_neg when they differ).
  bool assign(int node, Complex e, Complex f, double* state) const {
    const TreeNode& n = at(node);
    double* slots = state + n.state;
    slots[0] = std::imag(e);
    slots[1] = std::imag(f);
    bool holds = true;
    switch (n.kind) {
      case NodeKind::friction: holds = std::abs(f) <= std::min(p(n, 1), p(n, 2)); break;
      case NodeKind::slider:
        slots[0] = 0.0;
        holds = std::abs(f) <= std::min(p(n, 0), p(n, 1));
        break;
      case NodeKind::inerter: slots[2] = std::imag(2.0 / plan_.dt * (1.0 - z_inverse_) / (1.0 + z_inverse_) * e); break;
      case NodeKind::parallel:
        for (int i = 0; i < n.child_count; ++i) holds &= assign(child(n, i), e, stiffness(child(n, i)) * e, state);
        break;
      case NodeKind::series:
        for (int i = 0; i < n.child_count; ++i) {
          const int c = child(n, i);
          holds &= assign(c, at(c).kind == NodeKind::slider ? Complex{0.0} : f / stiffness(c), f, state);
        }
        break;
      default: break;
    }
    return holds;
  }

 private:
  const TreeNode& at(int node) const { return t_.nodes[static_cast<std::size_t>(node)]; }
  int child(const TreeNode& n, int i) const { return t_.children[static_cast<std::size_t>(n.first_child + i)]; }
  double p(const TreeNode& n, int slot) const { return network_.parameter(n.param[slot]); }
  double coefficient(int node) const { return plan_.coefficient[static_cast<std::size_t>(node)]; }

  const Topology& t_;
  const Network& network_;
  const TreeStepPlan& plan_;
  Complex z_inverse_;
};

}  // namespace

void set_periodic_start(const Network& network, const StepPlan& plan, double amplitude, int steps, State& state, double preload) {
  const Topology& t = network.topology();
  const Coefficients& c = network.coefficients();
  const Complex z = std::polar(1.0, 2.0 * std::numbers::pi / steps);
  for (std::size_t i = 0; i < c.maxwell_k.size(); ++i) {
    const double a = plan.maxwell_a[i], b = plan.maxwell_b[i];
    state.values[static_cast<std::size_t>(t.maxwell_state()) + i] = b * amplitude * std::imag((z - 1.0) / (z - a));
  }
  for (std::size_t i = 0; i < c.friction_k.size(); ++i) {
    const double k = c.friction_k[i], fy = c.friction_fy[i];
    state.values[static_cast<std::size_t>(t.friction_state()) + i] = amplitude > fy / k ? std::min(fy, k * amplitude - fy) : 0.0;
  }
  for (std::size_t i = 0; i < c.slider_fy.size(); ++i) state.values[static_cast<std::size_t>(t.slider_state()) + i] = -c.slider_fy[i];
  if (preload != 0.0) return;
  const LinearisedSubtree subtree(network, plan.tree, z);
  for (int root : t.subtrees) {
    if (!subtree.supported(root)) continue;
    const Complex e = amplitude;
    if (!subtree.assign(root, e, subtree.stiffness(root) * e, state.values.data())) subtree.assign(root, 0.0, 0.0, state.values.data());
  }
}

}  // namespace rheo::runtime
