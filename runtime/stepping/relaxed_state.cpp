#include "runtime/stepping/relaxed_state.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/network/monotone_solve.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rheo::runtime {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kRelTol = 1e-13;

struct Play {
  double lo, hi;  // mm: the elongations at which a node carries no force
  bool contains(double e) const { return e >= lo && e <= hi; }
};

bool is_free(NodeKind kind) {
  switch (kind) {
    case NodeKind::dashpot:
    case NodeKind::quadratic_dashpot:
    case NodeKind::maxwell:
    case NodeKind::inerter:
    case NodeKind::friction:
    case NodeKind::slider:
    case NodeKind::bouc_wen: return true;
    default: return false;
  }
}

class Relaxer {
 public:
  explicit Relaxer(const Network& network) : t_(network.topology()), network_(network) {}

  Play play(int node) const {
    const TreeNode& n = at(node);
    if (is_free(n.kind)) return {-kInf, kInf};
    switch (n.kind) {
      case NodeKind::gap: {
        const double c = gap_center(p(n, 0), p(n, 1));
        return {c - 0.5 * p(n, 0), c + 0.5 * p(n, 0)};
      }
      case NodeKind::parallel: {
        Play out{-kInf, kInf};
        for (int i = 0; i < n.child_count; ++i) {
          const Play c = play(child(n, i));
          out = {std::max(out.lo, c.lo), std::min(out.hi, c.hi)};
        }
        return out;
      }
      case NodeKind::series: {
        Play out{0.0, 0.0};
        for (int i = 0; i < n.child_count; ++i) {
          const Play c = play(child(n, i));
          out = {out.lo + c.lo, out.hi + c.hi};
        }
        return out;
      }
      default: return {0.0, 0.0};  // spring, yeoh
    }
  }

  // Relaxed force [N] of NODE at elongation e [mm], and dF/de [N/mm].
  ForceSlope force(int node, double e) const {
    const TreeNode& n = at(node);
    if (is_free(n.kind)) return {0.0, 0.0};
    switch (n.kind) {
      case NodeKind::spring: return {p(n, 0) * e, p(n, 0)};
      case NodeKind::yeoh: {
        const YeohLaw law = yeoh(n);
        return {law.force(e), law.slope(e)};
      }
      case NodeKind::poly_spring: {
        const PolyLaw law = poly(n);
        return {law.force(e), law.slope(e)};
      }
      case NodeKind::parallel: return sum_over_children(n, [&](int c) { return force(c, e); });
      case NodeKind::series: return series_force(node, e);
      default: throw std::logic_error("relaxed_state: a gap outside a series chain");
    }
  }

  // Relaxed elongation [mm] of NODE at force F != 0 [N] (0 at F = 0), and de/dF [mm/N].
  ForceSlope elongation(int node, double f) const {
    const TreeNode& n = at(node);
    if (f == 0.0 || is_free(n.kind)) return {0.0, 0.0};
    switch (n.kind) {
      case NodeKind::spring: return {f / p(n, 0), 1.0 / p(n, 0)};
      case NodeKind::gap: return {gap_center(p(n, 0), p(n, 1)) + std::copysign(0.5 * p(n, 0), f), 0.0};
      case NodeKind::yeoh: return yeoh_elongation(node, f);
      case NodeKind::poly_spring: return poly_elongation(node, f);
      case NodeKind::series: return sum_over_children(n, [&](int c) { return elongation(c, f); });
      case NodeKind::parallel: {
        const Play reach = play(node);
        auto residual = [&](double e) {
          const ForceSlope c = force(node, e);
          return ForceSlope{c.force - f, c.slope};
        };
        const double from = f > 0.0 ? reach.hi : reach.lo;
        const double e = checked(solve_monotone(residual, from, 1.0, f > 0.0 ? from : -kInf, f > 0.0 ? kInf : from, kRelTol * std::abs(f)));
        const double slope = force(node, e).slope;
        return {e, slope > 0.0 ? 1.0 / slope : 0.0};
      }
      default: return {0.0, 0.0};
    }
  }

  // Writes (e, F) of NODE and of everything below it into VALUES.
  void assign(int node, double e, double f, double* values) const {
    const TreeNode& n = at(node);
    values[n.state] = e;
    values[n.state + 1] = f;
    if (n.kind == NodeKind::parallel) {
      for (int i = 0; i < n.child_count; ++i) assign(child(n, i), e, force(child(n, i), e).force, values);
    } else if (n.kind == NodeKind::series) {
      if (f != 0.0) {
        for (int i = 0; i < n.child_count; ++i) assign(child(n, i), elongation(child(n, i), f).force, f, values);
        return;
      }
      // No force: the first free member takes everything; else the members' play, in order.
      int taker = -1;
      for (int i = 0; i < n.child_count && taker < 0; ++i)
        if (std::isinf(play(child(n, i)).hi)) taker = i;
      double rest = e;
      for (int i = 0; i < n.child_count; ++i) {
        const Play c = play(child(n, i));
        const double take = taker >= 0 ? (i == taker ? e : 0.0) : std::clamp(rest, c.lo, c.hi);
        rest -= take;
        assign(child(n, i), take, 0.0, values);
      }
    }
  }

 private:
  const TreeNode& at(int node) const { return t_.nodes[static_cast<std::size_t>(node)]; }
  int child(const TreeNode& n, int i) const { return t_.children[static_cast<std::size_t>(n.first_child + i)]; }
  double p(const TreeNode& n, int i) const { return network_.parameter(n.param[i]); }
  YeohLaw yeoh(const TreeNode& n) const { return {p(n, 0), p(n, 1), p(n, 2)}; }
  PolyLaw poly(const TreeNode& n) const { return {p(n, 0), p(n, 1), p(n, 2)}; }
  std::string path_of(int node, const char* kind) const {
    for (const auto& probe : t_.probes)
      if (probe.source == ElementProbe::Source::tree_node && probe.index == node) return fmt::format("{} '{}'", kind, probe.path);
    return fmt::format("a {}", kind);
  }
  // The children's values and slopes added: forces of a parallel block, elongations of a chain.
  template <class Of>
  ForceSlope sum_over_children(const TreeNode& n, Of of) const {
    ForceSlope sum{0.0, 0.0};
    for (int i = 0; i < n.child_count; ++i) {
      const ForceSlope c = of(child(n, i));
      sum = {sum.force + c.force, sum.slope + c.slope};
    }
    return sum;
  }
  // NaN from solve_monotone: its iteration cap was exhausted.
  double checked(double value) const {
    if (std::isnan(value))
      throw NumericalError(
          fmt::format("model '{}': the static equilibrium of its relaxed start did not converge within the iteration cap; "
                      "start the history from 0 (start = rest)",
                      network_.model().name));
    return value;
  }

  ForceSlope series_force(int node, double e) const {
    const Play reach = play(node);
    if (reach.contains(e) && reach.lo < reach.hi) return {0.0, 0.0};
    auto residual = [&](double f) {
      const ForceSlope c = elongation(node, f);
      return ForceSlope{c.force - e, c.slope};
    };
    const bool pulled = e > reach.hi;
    const double f = checked(solve_monotone(residual, 0.0, 1.0, pulled ? 0.0 : -kInf, pulled ? kInf : 0.0, kRelTol * (std::abs(e) + 1e-12)));
    const double compliance = elongation(node, f).slope;
    return {f, compliance > 0.0 ? 1.0 / compliance : 0.0};
  }

  // Elongation of a poly_spring at force f, within the range where its tangent is positive.
  ForceSlope poly_elongation(int node, double f) const {
    const PolyLaw law = poly(at(node));
    const PolyLaw::Range r = law.monotone_range();
    const double lo = std::isfinite(r.lo) ? law.force(r.lo) : -kInf, hi = std::isfinite(r.hi) ? law.force(r.hi) : kInf;
    if (!(f > lo && f < hi))
      throw ModelError(fmt::format("the relaxed start needs {} of model '{}' to carry {:g} N, more than its softening law can; {}",
                                   path_of(node, "poly_spring"), network_.model().name, f, PolyLaw::monotone_advice));
    auto residual = [&](double e) { return ForceSlope{law.force(e) - f, law.slope(e)}; };
    const double e = checked(solve_monotone(residual, 0.0, f / law.k1, r.lo, r.hi, kRelTol * std::abs(f)));
    return {e, 1.0 / law.slope(e)};
  }

  ForceSlope yeoh_elongation(int node, double f) const {
    const TreeNode& n = at(node);
    const YeohLaw law = yeoh(n);
    const double soft = law.softening_elongation();
    if (std::isfinite(soft) && !(std::abs(f) < std::abs(law.force(soft)))) {
      std::string path = "a yeoh spring";
      for (const auto& probe : t_.probes)
        if (probe.source == ElementProbe::Source::tree_node && probe.index == node) path = "yeoh spring '" + probe.path + "'";
      throw ModelError(fmt::format("the relaxed start needs {} of model '{}' to carry {:g} N, more than its softening law can; {}", path,
                                   network_.model().name, f, YeohLaw::monotone_advice));
    }
    auto residual = [&](double e) { return ForceSlope{law.force(e) - f, law.slope(e)}; };
    const double e = checked(solve_monotone(residual, 0.0, f / law.slope(0.0), std::isfinite(soft) ? -soft : -kInf,
                                            std::isfinite(soft) ? soft : kInf, kRelTol * std::abs(f)));
    return {e, 1.0 / law.slope(e)};
  }

  const Topology& t_;
  const Network& network_;
};

}  // namespace

State relaxed_state(const Network& network, double u0) {
  const Simulator simulator(network);
  State s = simulator.rest_state();
  if (u0 == 0.0) return s;
  const Topology& t = network.topology();
  const Coefficients& c = network.coefficients();
  double force = c.spring_k * u0;
  for (std::size_t i = 0; i < c.yeoh_d10.size(); ++i) force += YeohLaw{c.yeoh_d10[i], c.yeoh_d20[i], c.yeoh_d30[i]}.force(u0);
  const Relaxer relaxer(network);
  for (int root : t.subtrees) {
    const double f = relaxer.force(root, u0).force;
    relaxer.assign(root, u0, f, s.values.data());
    force += f;
  }
  s.u = u0;
  s.force = force;
  return s;
}

StartAtRest relaxed_start(const Network& network, const State& relaxed) {
  StartAtRest start;
  start.force = relaxed.force;
  Simulator(network).element_outputs(StepPlan::make(network, 1.0), relaxed, relaxed, start.element_force, start.element_elongation);
  return start;
}

}  // namespace rheo::runtime
