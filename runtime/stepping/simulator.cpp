#include "runtime/stepping/simulator.hpp"

#include <algorithm>

namespace rheo::runtime {

StepPlan StepPlan::make(const Network& network, double dt, double piece) {
  StepPlan plan;
  plan.dt = dt;
  const Coefficients& c = network.coefficients();
  for (std::size_t i = 0; i < c.maxwell_k.size(); ++i) {
    const MaxwellStep m = MaxwellStep::make(c.maxwell_k[i], c.maxwell_c[i], dt);
    plan.maxwell_a.push_back(m.a);
    plan.maxwell_b.push_back(m.b);
  }
  plan.dashpot_c_over_dt = c.dashpot_c / dt;
  plan.tree.prepare(network, dt, piece > dt ? piece : dt);
  return plan;
}

State Simulator::rest_state() const {
  State s;
  s.values.assign(static_cast<std::size_t>(network_.topology().state_size), 0.0);
  return s;
}

namespace {

// Simulator::step_root, inlined into Simulator::step.
[[gnu::always_inline]] inline double root_step(const Network& network, const StepPlan& plan, const State& before, double u_next, State& after) {
  const Topology& t = network.topology();
  const Coefficients& c = network.coefficients();
  const double du = u_next - before.u;
  const double* x = before.values.data();
  double* y = after.values.data();

  double force = c.spring_k * u_next + plan.dashpot_c_over_dt * du;
  for (std::size_t i = 0; i < c.yeoh_d10.size(); ++i) force += YeohLaw{c.yeoh_d10[i], c.yeoh_d20[i], c.yeoh_d30[i]}.force(u_next);

  const std::size_t nm = c.maxwell_k.size();
  const double* xm = x + t.maxwell_state();
  double* ym = y + t.maxwell_state();
  for (std::size_t i = 0; i < nm; ++i) {
    ym[i] = plan.maxwell_a[i] * xm[i] + plan.maxwell_b[i] * du;
    force += ym[i];
  }

  const std::size_t nf = c.friction_k.size();
  const double* xf = x + t.friction_state();
  double* yf = y + t.friction_state();
  for (std::size_t i = 0; i < nf; ++i) {
    const double fy = c.friction_fy[i];
    yf[i] = std::clamp(xf[i] + c.friction_k[i] * du, -fy, fy);
    force += yf[i];
  }

  const std::size_t ns = c.slider_fy.size();
  const double* xs = x + t.slider_state();
  double* ys = y + t.slider_state();
  for (std::size_t i = 0; i < ns; ++i) {
    // Driven directly, a stuck slider's force is not determined by the drive: it holds.
    const double fy = c.slider_fy[i];
    ys[i] = du > 0.0 ? fy : du < 0.0 ? -fy : std::clamp(xs[i], -fy, fy);
    force += ys[i];
  }
  return force;
}

}  // namespace

double Simulator::step(const StepPlan& plan, const State& before, double u_next, State& after, double time) const {
  double force = root_step(network_, plan, before, u_next, after);
  const Topology& t = network_.topology();
  if (!t.subtrees.empty()) {
    const TreeSolver solver(network_, plan.tree, before.values.data(), time);
    for (int root : t.subtrees) force += solver.advance(root, u_next - before.u, after.values.data());
  }
  after.u = u_next;
  after.force = force;
  return force;
}

double Simulator::step_root(const StepPlan& plan, const State& before, double u_next, State& after) const {
  return root_step(network_, plan, before, u_next, after);
}

void Simulator::element_outputs(const StepPlan& plan, const State& before, const State& after, std::vector<double>& force,
                                std::vector<double>& elongation) const {
  const Topology& t = network_.topology();
  const Coefficients& c = network_.coefficients();
  force.resize(t.probes.size());
  elongation.resize(t.probes.size());
  const double u = after.u;
  const double du = after.u - before.u;
  const auto* y = after.values.data();
  using Source = ElementProbe::Source;
  for (std::size_t i = 0; i < t.probes.size(); ++i) {
    const ElementProbe& probe = t.probes[i];
    const auto k = static_cast<std::size_t>(probe.index);
    double f = 0.0, e = u;
    switch (probe.source) {
      case Source::root_spring: f = network_.parameter(t.springs[k]) * u; break;
      case Source::root_yeoh: f = YeohLaw{c.yeoh_d10[k], c.yeoh_d20[k], c.yeoh_d30[k]}.force(u); break;
      case Source::root_dashpot: f = network_.parameter(t.dashpots[k]) * du / plan.dt; break;
      case Source::root_maxwell: f = y[t.maxwell_state() + probe.index]; break;
      case Source::root_friction: f = y[t.friction_state() + probe.index]; break;
      case Source::root_slider: f = y[t.slider_state() + probe.index]; break;
      case Source::root_springpot:
        for (int j = 0; j < probe.count; ++j) f += y[t.maxwell_state() + probe.index + j];
        break;
      case Source::tree_node:
      case Source::tree_maxwell_spring:
      case Source::tree_maxwell_dashpot: {
        const TreeNode& node = t.nodes[k];
        f = y[node.state + 1];
        e = y[node.state];
        const double spring_part = f / network_.parameter(node.param[0]);
        if (probe.source == Source::tree_maxwell_spring) e = spring_part;
        if (probe.source == Source::tree_maxwell_dashpot) e -= spring_part;
        break;
      }
    }
    force[i] = f;
    elongation[i] = e;
  }
}

}  // namespace rheo::runtime
