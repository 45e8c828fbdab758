#include "runtime/fit/thesis_approximation.hpp"

#include "runtime/core/parallel_for.hpp"
#include "runtime/network/leaf_kernels.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rheo::runtime {
namespace {

// The elements of Figs. 5.1/5.3 as the approximation needs them, read once per network.
struct ThesisElements {
  double elastic = 0.0;                         // K_e [N/mm]
  std::vector<double> maxwell_k, maxwell_tau;   // K_v [N/mm], t_r [s]
  std::vector<double> friction_k, friction_fy;  // K_p [N/mm], F_y = K_p u_s [N]
};

std::string reject(const ElementProbe& probe, const char* why) {
  return fmt::format(
      "{} '{}' {}; the thesis approximation (eqs. 5.12-5.21) covers springs, yeoh springs, Maxwell and "
      "friction elements in parallel only (Figs. 5.1, 5.3); use method = exact",
      lang::kind_word(probe.kind), probe.path, why);
}

bool is_subtree_root(const Topology& t, int node) { return std::find(t.subtrees.begin(), t.subtrees.end(), node) != t.subtrees.end(); }

ThesisElements thesis_elements(const Network& network) {
  if (const std::string why = approximation_misfit(network); !why.empty())
    throw std::logic_error(fmt::format("approximate_harmonic: model '{}': {}", network.model().name, why));
  const Topology& t = network.topology();
  const Coefficients& c = network.coefficients();
  ThesisElements e;
  e.elastic = c.spring_k;
  for (double d10 : c.yeoh_d10) e.elastic += 2.0 * d10;
  for (std::size_t j = 0; j < c.maxwell_k.size(); ++j) {
    e.maxwell_k.push_back(c.maxwell_k[j]);
    e.maxwell_tau.push_back(c.maxwell_c[j] / c.maxwell_k[j]);
  }
  for (int root : t.subtrees) {  // fused pairs, the only subtrees left after the checks above
    const TreeNode& node = t.nodes[static_cast<std::size_t>(root)];
    const double k = network.parameter(node.param[0]), damping = network.parameter(node.param[1]);
    e.maxwell_k.push_back(k);
    e.maxwell_tau.push_back(damping / k);
  }
  e.friction_k = c.friction_k;
  e.friction_fy = c.friction_fy;
  return e;
}

// Fills everything the thesis definition derives from K and d.
void set_measures(HarmonicPoint& p, double stiffness, double damping) {
  CycleMeasures& m = p.measures;
  m.stiffness = stiffness;
  m.damping = damping;
  m.damping_clamped = damping > 1.0;
  m.phase = std::asin(std::min(damping, 1.0));
  m.storage = stiffness * std::cos(m.phase);
  m.loss = stiffness * std::sin(m.phase);
  m.force_amplitude = stiffness * p.amplitude;
  m.energy = std::numbers::pi * m.force_amplitude * p.amplitude * damping;
}

HarmonicPoint approximate_point(const ThesisElements& e, double u0, double frequency) {
  const double w = 2.0 * std::numbers::pi * frequency;
  double storage = e.elastic, loss = 0.0;  // sums of K^{v,j} cos, sin delta_v^j (5.14)
  for (std::size_t j = 0; j < e.maxwell_k.size(); ++j) {
    // |K*_j| (see the header on 5.12) times cos and sin of delta_v^j = atan(1/x) (5.13): the
    // storage and loss stiffness, in the form that holds for any x = w t_r (leaf_kernels.hpp).
    const StorageLoss m = maxwell_storage_loss(e.maxwell_k[j], w * e.maxwell_tau[j]);
    storage += m.storage;
    loss += m.loss;
  }
  const double k_visco = std::hypot(storage, loss);             // (5.14)
  const double d_visco = k_visco > 0.0 ? loss / k_visco : 0.0;  // (5.15)

  double k_friction = 0.0, work = 0.0;
  for (std::size_t q = 0; q < e.friction_k.size(); ++q) {
    const double kp = e.friction_k[q], fy = e.friction_fy[q], us = fy / kp;
    const bool slips = us < u0;
    k_friction += slips ? fy / u0 : kp;       // (5.16), (5.18)
    if (slips) work += 4.0 * fy * (u0 - us);  // (5.17)
  }
  const double d_friction = work > 0.0 ? work / (std::numbers::pi * u0 * u0 * k_friction) : 0.0;  // (5.19)

  const double stiffness = k_visco + k_friction;                                     // (5.20)
  const double damping = (k_visco * d_visco + k_friction * d_friction) / stiffness;  // (5.21)
  HarmonicPoint p;
  p.amplitude = u0;
  p.frequency = frequency;
  p.converged = true;
  set_measures(p, stiffness, damping);
  return p;
}

bool same(double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b)); }

}  // namespace

std::string approximation_misfit(const Network& network) {
  const Topology& t = network.topology();
  for (const auto& probe : t.probes) {
    using S = ElementProbe::Source;
    switch (probe.source) {
      case S::root_spring:
      case S::root_yeoh:
      case S::root_maxwell:
      case S::root_springpot:  // its Maxwell chain
      case S::root_friction: break;
      case S::root_dashpot: return reject(probe, "is a dashpot (no elastic part)");
      case S::root_slider: return reject(probe, "is a rigid-plastic slider");
      case S::tree_maxwell_spring:
      case S::tree_maxwell_dashpot:
        if (is_subtree_root(t, probe.index)) break;  // a spring + dashpot pair in the root block
        return reject(probe, "sits inside a nested series/parallel block");
      case S::tree_node:  // a subtree root is an inerter, quadratic_dashpot, gap or bouc_wen leaf
        return reject(probe, is_subtree_root(t, probe.index) ? "is not covered" : "sits inside a nested series/parallel block");
    }
  }
  return {};
}

std::vector<HarmonicPoint> approximate_harmonic(const Network& network, const std::vector<double>& amplitudes,
                                                const std::vector<double>& frequencies, int threads) {
  if (amplitudes.size() != frequencies.size())
    throw std::logic_error(
        fmt::format("approximate_harmonic: {} amplitudes but {} frequencies (pointwise pairs)", amplitudes.size(), frequencies.size()));
  const ThesisElements elements = thesis_elements(network);
  for (std::size_t i = 0; i < amplitudes.size(); ++i)
    if (!(amplitudes[i] > 0.0) || !(frequencies[i] > 0.0))
      throw std::logic_error(fmt::format("approximate_harmonic: point {} has amplitude {} mm, frequency {} Hz; both must be > 0", i + 1,
                                         amplitudes[i], frequencies[i]));
  std::vector<HarmonicPoint> points(amplitudes.size());
  parallel_for(points.size(), threads, [&](std::size_t i) { points[i] = approximate_point(elements, amplitudes[i], frequencies[i]); });
  return points;
}

ThesisCorrection thesis_correction(const std::vector<HarmonicPoint>& approximate, const std::vector<HarmonicPoint>& numerical) {
  if (approximate.size() != numerical.size())
    throw std::logic_error(fmt::format("thesis_correction: {} approximate but {} numerical points", approximate.size(), numerical.size()));
  ThesisCorrection c;
  c.stiffness.reserve(approximate.size());
  c.damping.reserve(approximate.size());
  for (std::size_t i = 0; i < approximate.size(); ++i) {
    const HarmonicPoint& a = approximate[i];
    const HarmonicPoint& n = numerical[i];
    if (!same(a.amplitude, n.amplitude) || !same(a.frequency, n.frequency))
      throw std::logic_error(fmt::format("thesis_correction: point {} differs (approximate {} mm, {} Hz; numerical {} mm, {} Hz)", i + 1,
                                         a.amplitude, a.frequency, n.amplitude, n.frequency));
    c.stiffness.push_back(n.measures.stiffness / a.measures.stiffness);                              // (5.2)
    c.damping.push_back(a.measures.damping != 0.0 ? n.measures.damping / a.measures.damping : 1.0);  // (5.3)
  }
  return c;
}

void apply_correction(const ThesisCorrection& correction, std::vector<HarmonicPoint>& approximate) {
  if (correction.stiffness.size() != approximate.size() || correction.damping.size() != approximate.size())
    throw std::logic_error(fmt::format("apply_correction: {} correction factors for {} points", correction.stiffness.size(), approximate.size()));
  for (std::size_t i = 0; i < approximate.size(); ++i) {
    HarmonicPoint& p = approximate[i];
    set_measures(p, p.measures.stiffness * correction.stiffness[i], p.measures.damping * correction.damping[i]);  // (5.4)
  }
}

}  // namespace rheo::runtime
