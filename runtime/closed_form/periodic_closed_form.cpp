#include "runtime/closed_form/periodic_closed_form.hpp"

#include "runtime/closed_form/pwl_periodic.hpp"
#include "runtime/closed_form/pwl_warm_start.hpp"
#include "runtime/core/evaluation_context.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/network/leaf_kernels.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <complex>
#include <deque>
#include <numbers>
#include <vector>

namespace rheo::runtime {
namespace {

constexpr double half_pi = 0.5 * std::numbers::pi;
constexpr int samples_per_half_cycle = 32;
constexpr double grid_step = std::numbers::pi / samples_per_half_cycle;  // T/64 in phase, the event path's grid step

// Point j of the loading half's grid, and sin and cos there (j = 0..samples_per_half_cycle).
double grid_phase(int j) { return -half_pi + j * grid_step; }
const std::array<std::pair<double, double>, samples_per_half_cycle + 1>& grid_sine_cosine() {
  static const auto table = [] {
    std::array<std::pair<double, double>, samples_per_half_cycle + 1> t{};
    for (int j = 0; j <= samples_per_half_cycle; ++j) t[static_cast<std::size_t>(j)] = {std::sin(grid_phase(j)), std::cos(grid_phase(j))};
    return t;
  }();
  return table;
}

// The loading half of the steady cycle, theta in [-pi/2, pi/2], as the sum of
//   a sin(theta) + b cos(theta) + Y_odd(u) + sign E(u) + constant + sum over slipping frictions,
// u = u0 sin(theta), where a gathers every branch linear in u (springs, Maxwell K', frictions that
// never slip), Y_odd(u) = y1 u + y3 u^3 + y5 u^5 and E(u) = y2 u^2 + y4 u^4 the odd and even parts
// of the yeoh springs' Y(p + u) - Y(p) about the preload p. The unloading half is the loading
// half's mirror with the even part's sign turned (sign = -1): F(theta + pi) = -[F(theta) with -E];
// an event-driven branch that is not half-wave symmetric (PwlPeriodicState::half_wave) enters
// the mirror as -F_b(theta + pi). With `polarity` -1 the whole force is negated, so that the
// maximum found is -(the minimum).
// The per-friction arrays are scratch space reused from point to point (no allocation once
// they have grown).
struct LoadingHalf {
  double u0 = 0.0;
  double a = 0.0;                                   // N
  double b = 0.0;                                   // N
  double y1 = 0.0, y3 = 0.0, y5 = 0.0;              // odd part of the yeoh springs about p [N/mm^n]
  double y2 = 0.0, y4 = 0.0;                        // even part (0 without preload)
  double sign = 1.0;                                // of the even part: +1 loading, -1 mirrored unloading
  double polarity = 1.0;                            // +1: F, -1: -F
  double constant = 0.0;                            // sliders, N
  std::vector<double> slip_k, slip_fy, slip_theta;  // frictions with u0 > uy; theta_q where they start to slip
  std::vector<double> ends;                         // piece ends
  std::vector<const PwlPeriodicState*> branches;    // piecewise-linear subtrees, by events
  std::vector<double> samples;                      // a piece's sample phases
  std::vector<int> sample_grid;                     // their index on the half cycle's grid (-1: a piece's end)
  std::vector<double> branch_slopes, one_branch;    // the branches' dF/dtheta there

  void clear() {
    a = b = y1 = y3 = y5 = y2 = y4 = constant = 0.0;
    sign = polarity = 1.0;
    slip_k.clear(), slip_fy.clear(), slip_theta.clear(), ends.clear(), branches.clear();
  }
  double force(double theta) const {
    const double s = std::sin(theta);
    const double u = u0 * s;
    const double u2 = u * u;
    double f = a * s + b * std::cos(theta) + u * (y1 + u2 * (y3 + y5 * u2)) + sign * u2 * (y2 + y4 * u2) + constant;
    for (std::size_t q = 0; q < slip_k.size(); ++q) f += std::min(slip_fy[q], -slip_fy[q] + slip_k[q] * u0 * (1.0 + s));
    for (const PwlPeriodicState* branch : branches) f += mirrored(*branch) ? -branch->force(theta + std::numbers::pi) : branch->force(theta);
    return polarity * f;
  }
  bool mirrored(const PwlPeriodicState& branch) const { return sign < 0.0 && !branch.half_wave(); }
  bool half_wave() const {
    return y2 == 0.0 && y4 == 0.0 &&
           std::all_of(branches.begin(), branches.end(), [](const PwlPeriodicState* branch) { return branch->half_wave(); });
  }
  // Stiffness (dF/du) of the slipping frictions still elastic on the piece holding `piece_mid`.
  double elastic_stiffness_on(double piece_mid) const {
    double k = 0.0;
    for (std::size_t q = 0; q < slip_k.size(); ++q)
      if (piece_mid < slip_theta[q]) k += slip_k[q];
    return k;
  }
  // dF/dtheta and d2F/dtheta2 at theta (with its sin and cos) inside a piece whose elastic frictions add `k_elastic` [N/mm].
  void derivatives(double theta, double s, double c, double k_elastic, double& first, double& second) const {
    closed_form_derivatives(s, c, k_elastic, first, second);
    for (const PwlPeriodicState* branch : branches) {
      double f1 = 0.0, f2 = 0.0;
      if (mirrored(*branch)) {
        branch->derivatives(theta + std::numbers::pi, f1, f2);
        f1 = -f1, f2 = -f2;
      } else {
        branch->derivatives(theta, f1, f2);
      }
      first += f1, second += f2;
    }
    first *= polarity, second *= polarity;
  }
  // The same without the event-driven branches and the polarity.
  void closed_form_derivatives(double s, double c, double k_elastic, double& first, double& second) const {
    const double u = u0 * s, u2 = u * u;
    const double dy = y1 + u2 * (3.0 * y3 + 5.0 * y5 * u2) + sign * u * (2.0 * y2 + 4.0 * y4 * u2);
    const double d2y = u * (6.0 * y3 + 20.0 * y5 * u2) + sign * (2.0 * y2 + 12.0 * y4 * u2);
    const double in_phase = a + u0 * (dy + k_elastic);
    first = c * in_phase - b * s;
    second = -s * in_phase + c * c * u0 * u0 * d2y - b * c;
  }
  // The event-driven branches' dF/dtheta at the phases of `samples`, summed into
  // branch_slopes (each branch carried along its pieces: PwlPeriodicState::slopes).
  // On the grid (sample_grid[j] >= 0) the slopes the shooting recorded as its steady cycle
  // passed there (PwlPeriodicState::grid_slope; the loading half's grid point j is the cycle's
  // j - 16, or j + 16 for a mirrored branch); at a piece's ends by the branch's own flow.
  void sample_branch_slopes() {
    const std::size_t count = samples.size();
    branch_slopes.assign(count, 0.0);
    one_branch.resize(count);
    for (const PwlPeriodicState* branch : branches) {
      const bool mirror = mirrored(*branch);
      const double offset = mirror ? std::numbers::pi : 0.0;
      for (std::size_t j = 0; j < count; ++j) {
        const int index = sample_grid[j];
        if (index >= 0) one_branch[j] = branch->grid_slope(index - samples_per_half_cycle / 2 + (mirror ? samples_per_half_cycle : 0));
        else branch->slopes(&samples[j], 1, offset, &one_branch[j]);
      }
      for (std::size_t j = 0; j < count; ++j) branch_slopes[j] += mirror ? -one_branch[j] : one_branch[j];
    }
  }
  // A lower bound of dF/du over |u| <= u0 without the frictions' share (>= 0); only for a
  // yeoh part without an even part (no preload).
  double least_in_phase() const {
    const double s_max = u0 * u0;
    auto dy = [&](double s) { return y1 + s * (3.0 * y3 + 5.0 * y5 * s); };
    double least = std::min(dy(0.0), dy(s_max));
    if (y5 != 0.0) {
      const double s_star = -3.0 * y3 / (10.0 * y5);
      if (s_star > 0.0 && s_star < s_max) least = std::min(least, dy(s_star));
    }
    return a + u0 * least;
  }
};

// Root of dF/dtheta in [lo, hi] with dF(lo) > 0 >= dF(hi): Newton from the midpoint,
// bisecting whenever a step leaves the bracket.
double stationary_point(const LoadingHalf& h, double lo, double hi, double k_elastic) {
  double x = 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 100 && hi - lo > 1e-15; ++iteration) {
    double first = 0.0, second = 0.0;
    h.derivatives(x, std::sin(x), std::cos(x), k_elastic, first, second);
    if (first > 0.0) lo = x;
    else hi = x;
    const double newton = second < 0.0 ? x - first / second : lo - 1.0;
    const double next = (newton > lo && newton < hi) ? newton : 0.5 * (lo + hi);
    if (std::abs(next - x) <= 1e-16 * (1.0 + std::abs(x))) return next;
    x = next;
  }
  return x;
}

// The same with event-driven branches, between two samples of the slope, slope_lo > 0 >=
// slope_hi, the latter taken after hi where a piece ends there (a switch). Newton from the
// chord's root; a step that leaves the bracket takes the chord's root instead (bisection would
// crawl to a root on the bracket's end: the drive's turning point, where the slope reaches 0
// linearly, or a kink), and hi itself where the slope there is 0. The first time a step raises
// lo without Newton, the slope just inside hi (1e-9 of the bracket) is looked at: where F
// still rises there, hi is a kink (a slider starting to slip, a gap opening) and the answer.
double stationary_point_between(const LoadingHalf& h, double lo, double hi, double slope_lo, double slope_hi, double k_elastic) {
  auto chord = [&] { return lo + (hi - lo) * (slope_lo / (slope_lo - slope_hi)); };
  double x = chord();
  bool probe = true;
  for (int iteration = 0; iteration < 100 && hi - lo > 1e-15; ++iteration) {
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    double first = 0.0, second = 0.0;
    h.derivatives(x, std::sin(x), std::cos(x), k_elastic, first, second);
    if (first > 0.0) lo = x, slope_lo = first;
    else hi = x, slope_hi = first;
    double next = second < 0.0 ? x - first / second : lo - 1.0;
    // Converged: checked before the bracket's safeguard (a root on the end that x just became
    // would otherwise be approached by the chord and bisection, up to 45 steps to the same point).
    if (std::abs(next - x) <= 1e-16 * (1.0 + std::abs(x))) return next;
    if (!(next > lo && next < hi)) {
      if (probe && first > 0.0) {
        probe = false;
        const double near_end = hi - 1e-9 * (hi - lo);
        double rise = 0.0, unused = 0.0;
        h.derivatives(near_end, std::sin(near_end), std::cos(near_end), k_elastic, rise, unused);
        if (rise > 0.0) return hi;
        if (near_end > lo) hi = near_end, slope_hi = rise;
      }
      if (slope_hi == 0.0) return hi;
      next = chord();
    }
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - x) <= 1e-16 * (1.0 + std::abs(x))) return next;
    x = next;
  }
  return x;
}

// Raises `best` to the largest stationary value of F in the piece [lo, hi], and sets `at` to its
// phase, if that is larger: the slope sampled and each sign change from + to - polished by
// stationary_point. Without event-driven branches: at max(2, ceil(32 (hi - lo)/pi)) equal
// steps, sin and cos by rotation.
void piece_maximum_rotated(const LoadingHalf& h, double lo, double hi, double k_elastic, double& best, double& at) {
  auto consider = [&](double theta) {
    if (const double f = h.force(theta); f > best) best = f, at = theta;
  };
  const int samples = std::max(2, static_cast<int>(std::ceil(samples_per_half_cycle * (hi - lo) / std::numbers::pi)));
  const double step = (hi - lo) / samples, cos_step = std::cos(step), sin_step = std::sin(step);
  double s = std::sin(lo), c = std::cos(lo);
  double previous_slope = 0.0, unused = 0.0;
  h.closed_form_derivatives(s, c, k_elastic, previous_slope, unused);
  previous_slope *= h.polarity;
  for (int j = 1; j <= samples; ++j) {
    const double next_s = s * cos_step + c * sin_step;
    c = c * cos_step - s * sin_step;
    s = next_s;
    double slope = 0.0;
    h.closed_form_derivatives(s, c, k_elastic, slope, unused);
    slope *= h.polarity;
    if (previous_slope > 0.0 && slope <= 0.0) {
      const double left = lo + (j - 1) * step, right = j == samples ? hi : lo + j * step;
      consider(stationary_point(h, left, right, k_elastic));
    }
    previous_slope = slope;
  }
}

// The same with event-driven branches: samples at the piece's ends and the points of the half
// cycle's grid, theta_j = -pi/2 + j pi/32, between them (T/64 apart: the shooting's grid-step
// propagators carry a branch from one to the next, and sin and cos are tabulated).
void piece_maximum_on_grid(LoadingHalf& h, double lo, double hi, double k_elastic, double& best, double& at) {
  auto consider = [&](double theta) {
    if (const double f = h.force(theta); f > best) best = f, at = theta;
  };
  h.samples.assign(1, lo), h.sample_grid.assign(1, -1);  // grid index -1: a piece's end
  for (int j = static_cast<int>(std::floor((lo + half_pi) / grid_step)) + 1; j < samples_per_half_cycle && grid_phase(j) < hi; ++j)
    if (grid_phase(j) > lo) h.samples.push_back(grid_phase(j)), h.sample_grid.push_back(j);
  h.samples.push_back(hi), h.sample_grid.push_back(-1);
  h.sample_branch_slopes();
  double previous_slope = 0.0, unused = 0.0;
  h.closed_form_derivatives(std::sin(lo), std::cos(lo), k_elastic, previous_slope, unused);
  previous_slope = h.polarity * (previous_slope + h.branch_slopes[0]);
  const auto& table = grid_sine_cosine();
  for (std::size_t j = 1; j < h.samples.size(); ++j) {
    const double theta = h.samples[j];
    const int index = h.sample_grid[j];
    const double s = index < 0 ? std::sin(theta) : table[static_cast<std::size_t>(index)].first;
    const double c = index < 0 ? std::cos(theta) : table[static_cast<std::size_t>(index)].second;
    double slope = 0.0;
    h.closed_form_derivatives(s, c, k_elastic, slope, unused);
    slope = h.polarity * (slope + h.branch_slopes[j]);
    if (previous_slope > 0.0 && slope <= 0.0) consider(stationary_point_between(h, h.samples[j - 1], theta, previous_slope, slope, k_elastic));
    previous_slope = slope;
  }
}

// max F over the loading half (as h.sign and h.polarity make it). When dF/dtheta >= 0 on
// [-pi/2, 0] is guaranteed (every branch's in-phase stiffness non-negative, b >= 0), only
// [0, pi/2] is searched. `at` receives the phase theta where the maximum lies.
double loading_half_maximum(LoadingHalf& h, double& at) {
  const bool odd = h.y2 == 0.0 && h.y4 == 0.0;
  const double from = odd && h.polarity > 0.0 && h.branches.empty() && h.b >= 0.0 && h.least_in_phase() >= 0.0 ? 0.0 : -half_pi;
  h.ends.assign({from, half_pi});
  for (double t : h.slip_theta)
    if (t > from) h.ends.push_back(t);
  for (const PwlPeriodicState* branch : h.branches)
    for (double t : branch->switch_phases()) {
      // In [-pi/2, 3 pi/2); a mirrored branch's kinks lie half a period earlier.
      double theta = std::fmod((h.mirrored(*branch) ? t - std::numbers::pi : t) + half_pi, 2.0 * std::numbers::pi);
      if (theta < 0.0) theta += 2.0 * std::numbers::pi;
      theta -= half_pi;
      if (theta > from && theta < half_pi) h.ends.push_back(theta);
    }
  std::sort(h.ends.begin(), h.ends.end());
  double best = h.force(from);
  at = from;
  auto consider = [&](double theta) {
    if (const double f = h.force(theta); f > best) best = f, at = theta;
  };
  for (std::size_t p = 0; p + 1 < h.ends.size(); ++p) {
    const double lo = h.ends[p], hi = h.ends[p + 1];
    if (!(hi > lo)) continue;
    consider(hi);
    const double k_elastic = h.elastic_stiffness_on(0.5 * (lo + hi));
    if (h.branches.empty()) piece_maximum_rotated(h, lo, hi, k_elastic, best, at);
    else piece_maximum_on_grid(h, lo, hi, k_elastic, best, at);
  }
  return best;
}

using Complex = std::complex<double>;

// K* of a linear subtree at angular frequency omega [rad/s] (see the header).
Complex subtree_stiffness(const Network& network, int index, double omega) {
  const Topology& t = network.topology();
  const TreeNode& node = t.nodes[static_cast<std::size_t>(index)];
  auto p = [&](int slot) { return network.parameter(node.param[slot]); };
  const Complex i{0.0, 1.0};
  switch (node.kind) {
    case NodeKind::spring: return p(0);
    case NodeKind::dashpot: return i * omega * p(0);
    case NodeKind::inerter: return -p(0) * omega * omega;
    case NodeKind::maxwell: {
      const StorageLoss m = maxwell_storage_loss(p(0), omega * (p(1) / p(0)));
      return {m.storage, m.loss};
    }
    case NodeKind::parallel:
    case NodeKind::series: {
      Complex sum{0.0, 0.0};
      for (int c = 0; c < node.child_count; ++c) {
        const Complex k = subtree_stiffness(network, t.children[static_cast<std::size_t>(node.first_child + c)], omega);
        if (node.kind == NodeKind::parallel) sum += k;
        else if (k == Complex{0.0, 0.0}) return k;
        else sum += 1.0 / k;
      }
      return node.kind == NodeKind::parallel || sum == Complex{0.0, 0.0} ? sum : 1.0 / sum;
    }
    default: return 0.0;  // excluded by has_closed_form_periodic_state
  }
}

// A one-node subtree the closed form takes as a root branch: a poly_spring, or a friction
// element or slider with one-sided yield forces (network.hpp puts those in subtrees).
bool is_root_leaf_with_closed_form(const TreeNode& node) {
  return node.child_count == 0 && (node.kind == NodeKind::poly_spring || node.kind == NodeKind::friction || node.kind == NodeKind::slider);
}

// Whether the subtree below ROOT holds a gap (its play is fixed in space: not shift-invariant).
bool has_gap(const Topology& t, int root) {
  const TreeNode& node = t.nodes[static_cast<std::size_t>(root)];
  if (node.kind == NodeKind::gap) return true;
  for (int c = 0; c < node.child_count; ++c)
    if (has_gap(t, t.children[static_cast<std::size_t>(node.first_child + c)])) return true;
  return false;
}

}  // namespace

bool has_closed_form_periodic_state(const Network& network, bool event_driven) {
  const Topology& t = network.topology();
  thread_local PwlBranch branch;
  return std::all_of(t.subtrees.begin(), t.subtrees.end(), [&](int root) {
    const TreeNode& node = t.nodes[static_cast<std::size_t>(root)];
    return node.linear || is_root_leaf_with_closed_form(node) || (event_driven && PwlBranch::build(network, root, branch));
  });
}

HarmonicPoint closed_form_harmonic_point(const Network& network, double amplitude, double frequency, HarmonicDefinition definition, double preload) {
  if (auto point = try_closed_form_harmonic_point(network, amplitude, frequency, definition, preload)) return *point;
  throw NumericalError(fmt::format(
      "model '{}': the event-driven periodic state at {:g} mm and {:g} Hz did not settle (a slider or gap "
      "switching without end, no periodic state within 460 cycles, or a preload on a gap, whose play is fixed in space); use steady_state = time_stepping",
      network.model().name, amplitude, frequency));
}

std::optional<HarmonicPoint> try_closed_form_harmonic_point(const Network& network, double amplitude, double frequency,
                                                            HarmonicDefinition definition, double preload, double* peak_phase) {
  const Coefficients& c = network.coefficients();
  const double u0 = amplitude;
  const double omega = 2.0 * std::numbers::pi * frequency;
  const double pi = std::numbers::pi;

  thread_local LoadingHalf h;
  h.clear();
  h.u0 = u0;
  double storage = c.spring_k;        // K'_1 [N/mm]
  double loss = c.dashpot_c * omega;  // K''_1 [N/mm]; U = pi u0^2 K''_1 for every branch
  for (std::size_t i = 0; i < c.maxwell_k.size(); ++i) {
    const StorageLoss m = maxwell_storage_loss(c.maxwell_k[i], omega * (c.maxwell_c[i] / c.maxwell_k[i]));
    storage += m.storage;
    loss += m.loss;
  }
  // A deque: a state's modes are referred to by address (PwlPeriodicState is not copyable).
  thread_local std::deque<PwlPeriodicState> event_branches;
  thread_local PwlBranch branch;
  std::size_t events_used = 0;
  int cycles = 0;                                // followed by the event-driven branches
  double event_storage = 0.0, event_loss = 0.0;  // their force is summed by LoadingHalf::force, not by a and b
  // Root-block leaves in subtrees (is_root_leaf_with_closed_form): poly_spring coefficients
  // summed, and friction elements and sliders at their mean yield force (see the header).
  double k1 = 0.0, k2 = 0.0, k3 = 0.0;
  thread_local std::vector<std::pair<double, double>> frictions;  // k, fy
  thread_local std::vector<double> sliders;                       // fy
  frictions.clear(), sliders.clear();
  for (std::size_t i = 0; i < c.friction_k.size(); ++i) frictions.emplace_back(c.friction_k[i], c.friction_fy[i]);
  sliders.assign(c.slider_fy.begin(), c.slider_fy.end());
  for (int root : network.topology().subtrees) {
    const TreeNode& node = network.topology().nodes[static_cast<std::size_t>(root)];
    if (is_root_leaf_with_closed_form(node)) {
      const auto p = [&](int slot) { return network.parameter(node.param[slot]); };
      if (node.kind == NodeKind::poly_spring) k1 += p(0), k2 += p(1), k3 += p(2);
      if (node.kind == NodeKind::friction) frictions.emplace_back(p(0), 0.5 * (p(1) + p(2)));
      if (node.kind == NodeKind::slider) sliders.push_back(0.5 * (p(0) + p(1)));
      continue;
    }
    if (!node.linear) {
      if (!PwlBranch::build(network, root, branch)) throw std::logic_error("closed_form_harmonic_point: a subtree has no closed form");
      if (preload != 0.0 && has_gap(network.topology(), root)) return std::nullopt;  // its play is not centred on the drive
      if (event_branches.size() <= events_used) event_branches.emplace_back();
      // The evaluation's warm starts (pwl_warm_start.hpp), by the subtree's ordinal among the event-driven ones.
      const int ordinal = static_cast<int>(events_used);
      const EvaluationContext& context = evaluation_context();
      PwlPeriodicState& state = event_branches[events_used++];
      if (!state.solve(branch, u0, omega, context.start ? context.start->find(u0, omega, ordinal) : nullptr)) return std::nullopt;
      // Not where the cold start closed at once (no slider slips, no gap closes: the stuck linear
      // state is the periodic one, and stays so for nearby parameters).
      if (context.record && state.cycles() > 1) context.record->record(u0, omega, ordinal, state.start());
      cycles = std::max(cycles, state.cycles());
      event_storage += state.storage();
      event_loss += state.loss();
      continue;
    }
    const Complex k = subtree_stiffness(network, root, omega);
    storage += k.real();
    loss += k.imag();
  }
  for (std::size_t i = 0; i < events_used; ++i) h.branches.push_back(&event_branches[i]);
  h.a = u0 * storage;
  h.b = u0 * loss;
  storage += event_storage;
  loss += event_loss;
  double d10 = 0.0, d20 = 0.0, d30 = 0.0;
  for (std::size_t i = 0; i < c.yeoh_d10.size(); ++i) d10 += c.yeoh_d10[i], d20 += c.yeoh_d20[i], d30 += c.yeoh_d30[i];
  // Y(p + u) - Y(p) = sum_n Y^(n)(p) u^n / n! for Y(u) = 2 D10 u + 4 D20 u^3 + 6 D30 u^5 (eq. 3.3).
  const double p = preload, p2 = p * p;
  h.y1 = 2.0 * d10 + 12.0 * d20 * p2 + 30.0 * d30 * p2 * p2;
  h.y2 = 12.0 * d20 * p + 60.0 * d30 * p2 * p;
  h.y3 = 4.0 * d20 + 60.0 * d30 * p2;
  h.y4 = 30.0 * d30 * p;
  h.y5 = 6.0 * d30;
  // P(p + u) - P(p) for P(u) = k1 u + k2 u^2 + k3 u^3.
  h.y1 += k1 + 2.0 * k2 * p + 3.0 * k3 * p2;
  h.y2 += k2 + 3.0 * k3 * p;
  h.y3 += k3;
  // First harmonic of the odd part: the mean of u^3 sin and u^5 sin over a cycle is 3/4 u0^3, 5/8 u0^5;
  // the even part adds nothing to K*_1 nor to U (it is conservative and even in u).
  storage += h.y1 + 0.75 * h.y3 * u0 * u0 + 0.625 * h.y5 * u0 * u0 * u0 * u0;
  for (const auto& [k, fy] : frictions) {
    const double uy = fy / k;
    if (u0 <= uy) {
      h.a += k * u0;
      storage += k;
      continue;
    }
    const double s = 2.0 * uy / u0 - 1.0;
    const double theta = std::asin(s);
    h.slip_k.push_back(k);
    h.slip_fy.push_back(fy);
    h.slip_theta.push_back(theta);
    storage += k / pi * (theta + half_pi + s * std::cos(theta));
    loss += 4.0 * fy * (u0 - uy) / (pi * u0 * u0);
  }
  for (double fy : sliders) {
    h.constant += fy;
    loss += 4.0 * fy / (pi * u0);
  }

  HarmonicPoint point;
  point.amplitude = amplitude;
  point.frequency = frequency;
  point.converged = true;
  point.cycles = cycles;
  // A sinusoidal force a sin + b cos (linear branches only) peaks at sqrt(a^2 + b^2) within the
  // loading half when b >= 0 (the loss of a passive network).
  const bool sinusoidal = h.slip_k.empty() && h.branches.empty() && h.constant == 0.0 && h.y1 == 0.0 && h.y3 == 0.0 && h.y5 == 0.0;
  double force_amplitude = 0.0, at = std::numeric_limits<double>::quiet_NaN(), unused = 0.0;
  if (sinusoidal && h.b >= 0.0) {
    force_amplitude = std::hypot(h.a, h.b);
    at = std::atan2(h.a, h.b);  // a sin + b cos = F^ sin(theta + atan2(b, a)) peaks there
  } else if (h.half_wave()) {
    force_amplitude = loading_half_maximum(h, at);  // max F = -min F
  } else if (h.branches.empty()) {                  // (max F - min F) / 2, min F = -(max of the mirrored half)
    const double loading = loading_half_maximum(h, unused);
    h.sign = -1.0;
    force_amplitude = 0.5 * (loading + loading_half_maximum(h, unused));
  } else {
    // An uneven event-driven branch: its extrema may lie in either half, so max F and min F are
    // searched over both: max(F) = max(max of the loading half, -(max of -F's mirror)), ...
    double max_f = -std::numeric_limits<double>::infinity(), min_f = std::numeric_limits<double>::infinity();
    for (double sign : {1.0, -1.0}) {
      h.sign = sign;
      h.polarity = 1.0;
      const double up = loading_half_maximum(h, unused);  // loading: max F; mirrored: -min F over the unloading half
      h.polarity = -1.0;
      const double down = loading_half_maximum(h, unused);  // loading: -min F; mirrored: max F over the unloading half
      max_f = std::max(max_f, sign > 0.0 ? up : down);
      min_f = std::min(min_f, sign > 0.0 ? -down : -up);
    }
    force_amplitude = 0.5 * (max_f - min_f);
  }
  point.measures = measures_from(force_amplitude, storage, loss, u0, definition);
  if (peak_phase) *peak_phase = at;
  return point;
}

}  // namespace rheo::runtime
