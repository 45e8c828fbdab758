#include "runtime/stepping/tree_solver.hpp"

#include "runtime/core/errors.hpp"

#include "runtime/network/monotone_solve.hpp"
#include "runtime/stepping/tree_newton.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rheo::runtime {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
// Relative tolerance of the inner solves, on elongations [mm] and forces [N].
constexpr double kRelTol = 1e-13;

// Parallel forces and series compliances add; series force ranges intersect.
template <class Solver, class Fn>
ForceSlope add_over_children(const Solver& solver, const TreeNode& n, Fn&& fn) {
  ForceSlope sum{0.0, 0.0};
  for (int i = 0; i < n.child_count; ++i) {
    const ForceSlope c = fn(solver.child(n, i));
    sum.force += c.force;
    sum.slope += c.slope;
  }
  return sum;
}

template <class Solver, class Fn>
Interval combine_children(const Solver& solver, const TreeNode& n, bool intersect, Fn&& fn) {
  Interval r = intersect ? Interval{-kInf, kInf} : Interval{0.0, 0.0};
  for (int i = 0; i < n.child_count; ++i) {
    const Interval c = fn(solver.child(n, i));
    if (intersect) {
      r.lo = std::max(r.lo, c.lo);
      r.hi = std::min(r.hi, c.hi);
    } else {
      r.lo += c.lo;
      r.hi += c.hi;
    }
  }
  return r;
}
}  // namespace

void TreeStepPlan::prepare(const Network& network, double step, double piece_length) {
  const auto& nodes = network.topology().nodes;
  dt = step;
  piece = piece_length;
  maxwell.assign(nodes.size(), MaxwellStep{0.0, 0.0});
  coefficient.assign(nodes.size(), 0.0);
  bounds.assign(nodes.size(), Interval{-kInf, kInf});
  const auto& children = network.topology().children;
  for (std::size_t i = nodes.size(); i-- > 0;) {  // children follow their parent in `nodes`
    const TreeNode& n = nodes[i];
    auto p = [&](int slot) { return network.parameter(n.param[slot]); };
    switch (n.kind) {
      case NodeKind::friction: bounds[i] = {-p(2), p(1)}; break;
      case NodeKind::slider: bounds[i] = {-p(1), p(0)}; break;
      case NodeKind::bouc_wen: bounds[i] = {-p(2), p(2)}; break;  // approached, never reached
      case NodeKind::parallel:
      case NodeKind::series: {
        const bool intersect = n.kind == NodeKind::series;
        Interval r = intersect ? Interval{-kInf, kInf} : Interval{0.0, 0.0};
        for (int k = 0; k < n.child_count; ++k) {
          const Interval c = bounds[static_cast<std::size_t>(children[static_cast<std::size_t>(n.first_child + k)])];
          r = intersect ? Interval{std::max(r.lo, c.lo), std::min(r.hi, c.hi)} : Interval{r.lo + c.lo, r.hi + c.hi};
        }
        bounds[i] = r;
        break;
      }
      default: break;
    }
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const TreeNode& n = nodes[i];
    auto p = [&](int slot) { return network.parameter(n.param[slot]); };
    switch (n.kind) {
      case NodeKind::maxwell: maxwell[i] = MaxwellStep::make(p(0), p(1), dt); break;
      case NodeKind::dashpot: coefficient[i] = p(0) / dt; break;
      case NodeKind::quadratic_dashpot: coefficient[i] = p(0) / (dt * dt); break;
      case NodeKind::inerter: coefficient[i] = 4.0 * p(0) / (dt * dt); break;
      case NodeKind::yeoh: {
        const YeohLaw law{p(0), p(1), p(2)};
        const double e = law.softening_elongation();
        coefficient[i] = std::isfinite(e) ? std::abs(law.force(e)) : kInf;
        break;
      }
      default: break;
    }
  }
  newton.prepare(network, bounds, coefficient);
  work.resize(nodes.size());
}

std::string TreeSolver::path_of(int node) const {
  for (const ElementProbe& probe : topology_.probes)
    if (probe.source == ElementProbe::Source::tree_node && probe.index == node) return probe.path;
  return "?";
}

void TreeSolver::throw_not_converged(int node, const char* what) const {
  const TreeNode& n = at(node);
  const char* kind = n.kind == NodeKind::series ? "series chain" : n.kind == NodeKind::parallel ? "parallel block" : "element";
  const std::string path = path_of(node);
  const std::string where = path == "?" ? fmt::format("a {}", kind) : fmt::format("{} '{}'", kind, path);
  const std::string when = std::isnan(time_) ? std::string("a step") : fmt::format("the step ending at t = {:g} s", time_);
  throw NumericalError(
      fmt::format("model '{}': the fixed-step solve of {} ({}) did not converge within its iteration cap in {}; "
                  "sample the history more finely there, or run it with solver = sundials",
                  network_.model().name, where, what, when));
}

void TreeSolver::throw_softened(int node, double force) const {
  const TreeNode& n = at(node);
  const std::string path = path_of(node);
  if (n.kind == NodeKind::poly_spring) {
    const PolyLaw law{p(n, 0), p(n, 1), p(n, 2)};
    const PolyLaw::Range r = law.monotone_range();
    throw NumericalError(
        fmt::format("model '{}': poly_spring '{}' is asked to carry {:.6g} N, but its tangent stiffness k1 + 2 k2 e + 3 k3 e^2 reaches zero "
                    "(at e = {:.6g} mm and {:.6g} mm), so it carries at most {:.6g} N in compression and {:.6g} N in tension; a softening spring "
                    "in series cannot hold more (it would snap through). Keep the drive small enough, or {}",
                    network_.model().name, path, force, r.lo, r.hi, std::isfinite(r.lo) ? -law.force(r.lo) : kInf,
                    std::isfinite(r.hi) ? law.force(r.hi) : kInf, PolyLaw::monotone_advice));
  }
  const YeohLaw law{p(n, 0), p(n, 1), p(n, 2)};
  throw NumericalError(
      fmt::format("model '{}': yeoh '{}' is asked to carry {:.6g} N, but its tangent stiffness 2 D10 + 12 D20 e^2 + 30 D30 e^4 reaches "
                  "zero at |e| = {:.6g} mm, where it carries its most, {:.6g} N (eq. 3.3); a softening spring in series cannot hold "
                  "a larger force (it would snap through). Keep the drive small enough that its elongation stays below that, or {}",
                  network_.model().name, path, force, law.softening_elongation(), coefficient(node), YeohLaw::monotone_advice));
}

bool steps_without_iteration(const Topology& topology) {
  return std::all_of(topology.nodes.begin(), topology.nodes.end(),
                     [](const TreeNode& n) { return n.kind != NodeKind::series || n.linear || n.capped_linear || n.rigid_when_stuck; });
}

ForceSlope TreeSolver::inerter(int node, double de) const {
  const TreeNode& n = at(node);
  if (n.drive_prescribed) {
    const auto rule = PrescribedInerter::make(plan_.dt, plan_.piece, slot_before(n, 4), slot_before(n, 5));
    return rule(p(n, 0), plan_.dt, slot_before(n, 2), slot_before(n, 3), de);
  }
  return InerterStep{coefficient(node), plan_.dt}(f_before(n), slot_before(n, 2), de);
}

ForceSlope TreeSolver::affine(int node) const {
  const TreeNode& n = at(node);
  if (n.kind == NodeKind::parallel) return add_over_children(*this, n, [&](int c) { return affine(c); });
  if (n.kind != NodeKind::series) return forward(node, 0.0);
  double compliance = 0.0, offset = 0.0;  // sum 1/S_i [mm/N], sum F0_i/S_i [mm]
  for (int i = 0; i < n.child_count; ++i) {
    const ForceSlope c = affine(child(n, i));
    compliance += 1.0 / c.slope;
    offset += c.force / c.slope;
  }
  return {offset / compliance, 1.0 / compliance};
}

ForceSlope TreeSolver::capped_linear(int node, double de, Interval cap) const {
  const TreeNode& n = at(node);
  double compliance = 0.0, offset = 0.0;
  for (int i = 0; i < n.child_count; ++i) {
    const int c = child(n, i);
    const TreeNode& m = at(c);
    if (m.kind == NodeKind::slider) continue;
    const ForceSlope a = m.kind == NodeKind::friction ? ForceSlope{f_before(m), p(m, 0)} : affine(c);
    compliance += 1.0 / a.slope;
    offset += a.force / a.slope;
  }
  const double trial = (de + offset) / compliance;
  if (trial >= cap.hi) return {cap.hi, 0.0};
  if (trial <= cap.lo) return {cap.lo, 0.0};
  return {trial, 1.0 / compliance};
}

ForceSlope TreeSolver::forward(int node, double de) const {
  const TreeNode& n = at(node);
  if (n.linear && n.child_count > 0) {
    const ForceSlope a = affine(node);
    return {a.force + a.slope * de, a.slope};
  }
  switch (n.kind) {
    case NodeKind::spring: return {p(n, 0) * (e_before(n) + de), p(n, 0)};
    case NodeKind::yeoh: {
      const YeohLaw law{p(n, 0), p(n, 1), p(n, 2)};
      const double e = e_before(n) + de;
      return {law.force(e), law.slope(e)};
    }
    case NodeKind::dashpot: return dashpot_step(coefficient(node), de);
    case NodeKind::quadratic_dashpot: return quadratic_dashpot_step(coefficient(node), de);
    case NodeKind::inerter: return inerter(node, de);
    case NodeKind::bouc_wen: {
      const ForceSlope r = BoucWenLaw{p(n, 0), p(n, 1), p(n, 2)}.step(f_before(n), de);
      checked(r.force, node, "bouc_wen loading law");
      return r;
    }
    case NodeKind::poly_spring: {
      const PolyLaw law{p(n, 0), p(n, 1), p(n, 2)};
      const double e = e_before(n) + de;
      return {law.force(e), law.slope(e)};
    }
    case NodeKind::gap: return {0.0, 0.0};  // only ever inverted (a direct member of a chain)
    case NodeKind::maxwell: return plan_.maxwell[static_cast<std::size_t>(node)](f_before(n), de);
    case NodeKind::friction: return friction_step(p(n, 0), p(n, 1), p(n, 2), f_before(n), de);
    case NodeKind::slider: {
      const double fy_pos = p(n, 0), fy_neg = p(n, 1);
      if (de > 0.0) return {fy_pos, 0.0};
      if (de < 0.0) return {-fy_neg, 0.0};
      return {std::clamp(f_before(n), -fy_neg, fy_pos), 0.0};
    }
    case NodeKind::parallel: return add_over_children(*this, n, [&](int c) { return forward(c, de); });
    case NodeKind::series: return series_force(node, de);
  }
  return {0.0, 0.0};
}

ForceSlope TreeSolver::forward_at_rest(int node, double direction) const {
  const TreeNode& n = at(node);
  const double f = f_before(n);
  switch (n.kind) {
    case NodeKind::friction: {  // elastic unless pushed beyond the cap it holds
      const bool slips = (direction > 0.0 && f >= p(n, 1)) || (direction < 0.0 && f <= -p(n, 2));
      return {f, slips ? 0.0 : p(n, 0)};
    }
    case NodeKind::bouc_wen: {  // unloading (z against the direction) is elastic
      const BoucWenLaw law{p(n, 0), p(n, 1), p(n, 2)};
      const double w = (direction > 0.0 ? 1.0 : -1.0) * f / law.fy;
      return {f, w < 0.0 ? law.k : law.k * law.rate(w)};
    }
    default: return forward(node, 0.0);
  }
}

Interval TreeSolver::zero_rate_interval(int node) const {
  const TreeNode& n = at(node);
  if (!n.rigid_when_stuck) {
    const double f = forward(node, 0.0).force;
    return {f, f};
  }
  switch (n.kind) {
    case NodeKind::slider: return {-p(n, 1), p(n, 0)};
    default:  // a parallel block, or a series of rigid members
      return combine_children(*this, n, n.kind == NodeKind::series, [&](int c) { return zero_rate_interval(c); });
  }
}

ForceSlope TreeSolver::inverse(int node, double force) const {
  const TreeNode& n = at(node);
  if (n.linear && n.child_count > 0) {
    const ForceSlope a = affine(node);
    return {(force - a.force) / a.slope, 1.0 / a.slope};
  }
  switch (n.kind) {
    case NodeKind::spring: return {force / p(n, 0) - e_before(n), 1.0 / p(n, 0)};
    case NodeKind::yeoh: {
      const YeohLaw law{p(n, 0), p(n, 1), p(n, 2)};
      if (!(std::abs(force) < coefficient(node))) throw_softened(node, force);
      auto residual = [&](double e) { return ForceSlope{law.force(e) - force, law.slope(e)}; };
      const double tol = kRelTol * (std::abs(force) + 1e-9);
      // Within the monotone range |e| < e* (law.force(+-e*) = +-coefficient bracket F).
      const double peak = law.softening_elongation();
      const double e = checked(
          solve_monotone(residual, std::clamp(e_before(n), -peak, peak), force / law.slope(0.0), -peak, peak, tol, true, plan_.iteration_cap), node,
          "yeoh elongation");
      return {e - e_before(n), 1.0 / law.slope(e)};
    }
    case NodeKind::poly_spring: {
      const PolyLaw law{p(n, 0), p(n, 1), p(n, 2)};
      const PolyLaw::Range r = law.monotone_range();
      if (!(force > (std::isfinite(r.lo) ? law.force(r.lo) : -kInf) && force < (std::isfinite(r.hi) ? law.force(r.hi) : kInf)))
        throw_softened(node, force);
      auto residual = [&](double e) { return ForceSlope{law.force(e) - force, law.slope(e)}; };
      const double tol = kRelTol * (std::abs(force) + 1e-9);
      const double start = std::clamp(e_before(n), std::nextafter(r.lo, 0.0), std::nextafter(r.hi, 0.0));
      const double e = checked(solve_monotone(residual, start, force / law.k1, r.lo, r.hi, tol, true, plan_.iteration_cap), node,
                               "poly_spring elongation");
      return {e - e_before(n), 1.0 / law.slope(e)};
    }
    case NodeKind::dashpot: {
      const double b = coefficient(node);
      return {force / b, 1.0 / b};
    }
    case NodeKind::quadratic_dashpot: return quadratic_dashpot_inverse(coefficient(node), force);
    case NodeKind::inerter: {
      if (!n.drive_prescribed) return InerterStep{coefficient(node), plan_.dt}.inverse(f_before(n), slot_before(n, 2), force);
      const ForceSlope at_rest = inerter(node, 0.0);  // linear in de
      return {(force - at_rest.force) / at_rest.slope, 1.0 / at_rest.slope};
    }
    case NodeKind::bouc_wen: {
      const ForceSlope r = BoucWenLaw{p(n, 0), p(n, 1), p(n, 2)}.inverse(f_before(n), force);
      checked(r.force, node, "bouc_wen inverse loading law");
      return r;
    }
    case NodeKind::gap: {  // at an end stop; at F = 0 it holds (chains resolve the play first)
      const Interval stop = stops(n);
      return {(force > 0.0 ? stop.hi : force < 0.0 ? stop.lo : std::clamp(e_before(n), stop.lo, stop.hi)) - e_before(n), 0.0};
    }
    case NodeKind::maxwell: {
      const MaxwellStep& m = plan_.maxwell[static_cast<std::size_t>(node)];
      return {(force - m.a * f_before(n)) / m.b, 1.0 / m.b};
    }
    case NodeKind::friction: {
      const double k = p(n, 0);
      return {((plan_.clamp_friction ? std::clamp(force, -p(n, 2), p(n, 1)) : force) - f_before(n)) / k, 1.0 / k};
    }
    case NodeKind::slider: return {0.0, 0.0};
    case NodeKind::series: return add_over_children(*this, n, [&](int c) { return inverse(c, force); });
    case NodeKind::parallel: return parallel_elongation(node, force);
  }
  return {0.0, 0.0};
}

ForceSlope TreeSolver::series_force(int node, double de) const {
  const TreeNode& n = at(node);
  const Interval cap = bounds(node);
  if (n.rigid_when_stuck) {  // only sliders (possibly in parallel): rigid until the cap slips
    if (de > 0.0) return {cap.hi, 0.0};
    if (de < 0.0) return {cap.lo, 0.0};
    const Interval z = zero_rate_interval(node);
    return {std::clamp(f_before(n), z.lo, z.hi), 0.0};
  }
  if (n.capped_linear) return capped_linear(node, de, cap);
  auto residual = [&](double force) {
    const ForceSlope e = inverse(node, force);
    return ForceSlope{e.force - de, e.slope};
  };
  const double tol = kRelTol * (std::abs(de) + std::abs(e_before(n)) + 1e-9);
  Interval domain = cap;
  if (has_gap(n)) {  // inside the play the chain is free; beyond it the force has de's side
    const Interval free = play(n);
    if (de >= free.lo && de <= free.hi) return {0.0, 0.0};
    (de > free.hi ? domain.lo : domain.hi) = 0.0;
  }
  if (std::isfinite(cap.hi) && residual(cap.hi).force <= 0.0) return {cap.hi, 0.0};
  if (std::isfinite(cap.lo) && residual(cap.lo).force >= 0.0) return {cap.lo, 0.0};
  const double start = std::clamp(f_before(n), domain.lo, domain.hi);
  const double force = checked(solve_monotone(residual, start, 1.0, domain.lo, domain.hi, tol, true, plan_.iteration_cap), node,
                               "common force of the chain");
  const double compliance = inverse(node, force).slope;
  return {force, compliance > 0.0 ? 1.0 / compliance : kInf};
}

ForceSlope TreeSolver::parallel_elongation(int node, double force) const {
  const TreeNode& n = at(node);
  double lo = -kInf, hi = kInf;
  bool leftmost = true;
  if (n.rigid_when_stuck) {
    const Interval z = zero_rate_interval(node);
    if (force >= z.lo && force <= z.hi) return {0.0, 0.0};
    if (force > z.hi) lo = 0.0;
    else hi = 0.0, leftmost = false;
  } else {
    leftmost = force >= forward(node, 0.0).force;
  }
  auto residual = [&](double de) {
    const ForceSlope f = forward(node, de);
    return ForceSlope{f.force - force, f.slope};
  };
  const double tol = kRelTol * (std::abs(force) + 1e-9);
  const double start = std::isfinite(lo) ? 1e-12 : (std::isfinite(hi) ? -1e-12 : 0.0);
  const double de = checked(solve_monotone(residual, start, 1e-3, lo, hi, tol, leftmost, plan_.iteration_cap), node,
                            "common elongation of the block");
  const double stiffness = forward(node, de).slope;
  return {de, stiffness > 0.0 ? 1.0 / stiffness : kInf};
}

bool TreeSolver::has_gap(const TreeNode& n) const {
  for (int i = 0; i < n.child_count; ++i)
    if (at(child(n, i)).kind == NodeKind::gap) return true;
  return false;
}

Interval TreeSolver::play(const TreeNode& n) const {
  Interval r{0.0, 0.0};
  for (int i = 0; i < n.child_count; ++i) {
    const TreeNode& c = at(child(n, i));
    if (c.kind == NodeKind::gap) {
      const Interval stop = stops(c);
      r.lo += stop.lo - e_before(c);
      r.hi += stop.hi - e_before(c);
    } else {
      const double d = inverse(child(n, i), 0.0).force;
      r.lo += d;
      r.hi += d;
    }
  }
  return r;
}

// F = 0 inside the play: the other members take their zero-force elongations, the gaps share
// the rest in order within their play, and the last gap takes the rounding remainder.
void TreeSolver::assign_play(const TreeNode& n, double de, double* after) const {
  double rest = de;
  int last_gap = -1;
  for (int i = 0; i < n.child_count; ++i)
    if (at(child(n, i)).kind != NodeKind::gap) rest -= inverse(child(n, i), 0.0).force;
    else last_gap = child(n, i);
  for (int i = 0; i < n.child_count; ++i) {
    const int c = child(n, i);
    const TreeNode& m = at(c);
    if (m.kind != NodeKind::gap) {
      assign(c, inverse(c, 0.0).force, 0.0, after);
      continue;
    }
    const Interval stop = stops(m);
    const double share = c == last_gap ? rest : std::clamp(rest, stop.lo - e_before(m), stop.hi - e_before(m));
    after[m.state] = e_before(m) + share;
    after[m.state + 1] = 0.0;
    rest -= share;
  }
}

void TreeSolver::assign(int node, double de, double force, double* after) const {
  const TreeNode& n = at(node);
  after[n.state] = e_before(n) + de;
  after[n.state + 1] = force;
  switch (n.kind) {
    case NodeKind::inerter: assign_inerter(node, de, after); return;
    case NodeKind::gap: {  // exactly at the stop when loaded
      const Interval stop = stops(n);
      after[n.state] = force > 0.0 ? stop.hi : force < 0.0 ? stop.lo : std::clamp(after[n.state], stop.lo, stop.hi);
      return;
    }
    case NodeKind::parallel: assign_parallel(n, de, force, after); return;
    case NodeKind::series: assign_series(node, de, force, after); return;
    default: return;  // leaves: elongation and force are their whole step state here
  }
}

void TreeSolver::assign_inerter(int node, double de, double* after) const {
  const TreeNode& n = at(node);
  if (n.drive_prescribed) {
    after[n.state + 2] = de / plan_.dt;
    after[n.state + 3] = slot_before(n, 2);
    after[n.state + 4] = plan_.dt;
    after[n.state + 5] = slot_before(n, 4);
  } else {
    after[n.state + 2] = InerterStep{coefficient(node), plan_.dt}.velocity_after(slot_before(n, 2), de);
  }
}

void TreeSolver::assign_parallel(const TreeNode& n, double de, double force, double* after) const {
  if (de != 0.0 || !n.rigid_when_stuck) {
    for (int i = 0; i < n.child_count; ++i) assign(child(n, i), de, forward(child(n, i), de).force, after);
    return;
  }
  // Stuck: rigid children carry whatever the compliant ones leave, within their intervals.
  double remainder = force;
  for (int i = 0; i < n.child_count; ++i)
    if (!at(child(n, i)).rigid_when_stuck) remainder -= forward(child(n, i), 0.0).force;
  int last_rigid = -1;
  for (int i = 0; i < n.child_count; ++i) {
    const int c = child(n, i);
    if (!at(c).rigid_when_stuck) {
      assign(c, 0.0, forward(c, 0.0).force, after);
      continue;
    }
    last_rigid = c;
    const Interval z = zero_rate_interval(c);
    const double share = std::clamp(remainder, z.lo, z.hi);
    assign(c, 0.0, share, after);
    remainder -= share;
  }
  if (remainder != 0.0 && last_rigid >= 0) after[at(last_rigid).state + 1] += remainder;
}

void TreeSolver::assign_series(int node, double de, double force, double* after) const {
  const TreeNode& n = at(node);
  if (force == 0.0 && has_gap(n)) {
    assign_play(n, de, after);
    return;
  }
  // Members take their elongation at the common force; at the cap, the first member whose
  // bound is reached slips and takes what the others leave.
  const Interval cap = bounds(node);
  const bool capped = force >= cap.hi || force <= cap.lo || n.rigid_when_stuck;
  int slipping = -1;
  for (int i = 0; i < n.child_count && capped && slipping < 0; ++i) {
    const Interval b = bounds(child(n, i));
    if (force >= b.hi || force <= b.lo || (n.rigid_when_stuck && de == 0.0)) slipping = child(n, i);
  }
  // Interior: the most compliant member takes the rounding remainder (a saturated bouc_wen, not
  // the spring beside it, which would be stretched beyond fy/k; never a block stuck at zero
  // rate, whose rigid members would be stored slipping). Linear and capped-linear chains (closed
  // forms): the last member not a gap.
  double most = 0.0;
  for (int i = 0; i < n.child_count && slipping < 0 && !n.linear && !n.capped_linear; ++i)
    if (at(child(n, i)).kind != NodeKind::gap) most = std::max(most, inverse(child(n, i), force).slope);
  for (int i = 0; i < n.child_count && slipping < 0 && most > 0.0; ++i)
    if (at(child(n, i)).kind != NodeKind::gap && inverse(child(n, i), force).slope == most) slipping = child(n, i);
  for (int i = n.child_count - 1; i >= 0 && slipping < 0; --i)
    if (at(child(n, i)).kind != NodeKind::gap) slipping = child(n, i);
  double taken = 0.0;
  for (int i = 0; i < n.child_count; ++i) {
    const int c = child(n, i);
    if (c == slipping) continue;
    const double e = inverse(c, force).force;
    taken += e;
    assign(c, e, force, after);
  }
  if (slipping >= 0) assign(slipping, de - taken, force, after);
}

double TreeSolver::advance(int node, double de, double* after) const {
  if (plan_.global_newton && plan_.newton.iterative[static_cast<std::size_t>(node)]) {
    double force = 0.0;
    if (TreeNewton(*this, plan_).advance(node, de, after, force)) return force;
    ++plan_.work.fallbacks;
  }
  return advance_nested(node, de, after);
}

double TreeSolver::advance_nested(int node, double de, double* after) const {
  const double force = forward(node, de).force;
  assign(node, de, force, after);
  return force;
}

}  // namespace rheo::runtime
