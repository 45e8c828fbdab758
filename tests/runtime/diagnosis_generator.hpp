// A second generator of measurements with a known truth for rheo diagnose, independent of
// diagnosis_support.hpp's (one 6 x 6 grid, 1 % and 0.15 deg Gaussian noise): every draw from a
// seed varies what a rig varies.
//   Harmonic grids: 4-8 amplitude levels log-uniform in [0.03, 3] mm and 4-9 frequency levels
//     in [0.5, 60] Hz, unevenly spaced, and up to 15 % of the points missing. Stiffness noise
//     relative (SD s of K/K_exp) or of the force amplitude (SD 0.4 s K_ref a_ref / (K a), K_ref
//     and a_ref geometric means: larger at small amplitudes); phase noise in degrees (0.05-0.3) or none.
//   Histories: 1-3 files of sines (or triangles) at different rates, 2-4 repeated cycles per
//     amplitude, 80-400 samples per cycle; force noise absolute (SD s max|F|) or relative to
//     the force (SD s (0.2 max|F| + |F|)).
//   Either: heteroscedastic (the SD up to 1 + h times larger towards small amplitudes) and/or
//     heavy-tailed (Student's t with 5 degrees of freedom scaled to unit variance), both drawn.
// The truth is a spring, a Maxwell and a friction element with drawn values; the start model is
// that structure from generic values, without the element the hidden effect removes, and the
// hidden effect's element is added to the truth (Hidden). The generator knows the noise SD of
// every term, so an estimate of the noise can be compared with the true one.
#pragma once

#include "diagnosis_support.hpp"
#include "portable_random.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/protocols/run_history.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace rheo::test::generated {

enum class Hidden {
  none,            // the start model has the truth's structure: the verdict must be none
  friction,        // the start lacks the friction element: amplitude-dependence
  maxwell,         // the start lacks the Maxwell element: rate-dependence
  column,          // a resonating fluid column added: inertia
  play,            // a spring behind off-centre free play added: backlash
  split_yield,     // histories: the friction element's yield differs in tension and compression: asymmetry
  even_spring,     // histories: the spring has a k2 u^2 term: asymmetry
  capped_maxwell,  // histories: a slider-capped Maxwell arm added: coupled-amplitude-frequency
  offset,          // histories: each file's force carries a constant (a load cell's zero), 2-10 % of max|F| either sign: offset
};

inline const char* hidden_name(Hidden h) {
  switch (h) {
    case Hidden::none: return "none";
    case Hidden::friction: return "friction";
    case Hidden::maxwell: return "maxwell";
    case Hidden::column: return "column";
    case Hidden::play: return "play";
    case Hidden::split_yield: return "split-yield";
    case Hidden::even_spring: return "even-spring";
    case Hidden::capped_maxwell: return "capped-maxwell";
    case Hidden::offset: return "offset";
  }
  return "?";
}

struct Scenario {
  std::string truth, start, description;
  std::vector<runtime::FitDataSet> data;
  // The true noise, as noise_estimate.hpp reports it: harmonic RMS over points of the SD of
  // K/K_exp - 1 and of the phase [rad], and the floor sqrt(sum s_K^2 + s_d^2)/n of err (6.1);
  // histories: RMS over files of the RMS force noise SD over max|F_exp|.
  double stiffness = 0.0, phase = 0.0, floor = 0.0, force = 0.0;
  std::vector<double> offsets;  // Hidden offset: each history file's [N]
};

// Unit-variance noise: Gaussian, or Student's t with 5 degrees of freedom scaled by sqrt(3/5).
inline double unit_noise(PortableRandom& random, bool heavy) {
  const double z = random.normal();
  if (!heavy) return z;
  double chi2 = 0.0;
  for (int k = 0; k < 5; ++k) chi2 += std::pow(random.normal(), 2);
  return z / std::sqrt(chi2 / 5.0) * std::sqrt(3.0 / 5.0);
}

// N distinct levels, log-uniform in [LO, HI], sorted; the first and last at the ends.
inline std::vector<double> uneven_levels(PortableRandom& random, int n, double lo, double hi) {
  std::vector<double> v{lo, hi};
  while (static_cast<int>(v.size()) < n) {
    const double x = lo * std::pow(hi / lo, random.unit());
    if (std::none_of(v.begin(), v.end(), [&](double y) { return std::abs(std::log(x / y)) < 0.08; })) v.push_back(x);
  }
  std::sort(v.begin(), v.end());
  for (double& x : v) x = std::round(x * 1e4) / 1e4;  // as a rig's table states them
  return v;
}

struct BaseValues {
  double k, km, tau_ms, kf, uy_um;
};

inline std::string truth_with(const BaseValues& b, Hidden h, PortableRandom& random, double a_max, double f_mid) {
  const bool split = h == Hidden::split_yield, even = h == Hidden::even_spring;
  std::string spring = even ? fmt::format("poly_spring s (k1 = {:.4g} N/mm, k2 = {:.4g} N/mm^2)", b.k, b.k * random.uniform(0.06, 0.15) / a_max)
                            : fmt::format("spring s (k = {:.4g} N/mm)", b.k);
  const double fy = b.kf * b.uy_um * 1e-3;  // N
  std::string friction = split ? fmt::format("friction f (k = {:.4g} N/mm, fy_pos = {:.4g} N, fy_neg = {:.4g} N)", b.kf, fy,
                                             fy * random.uniform(1.6, 2.5))
                               : fmt::format("friction f (k = {:.4g} N/mm, uy = {:.4g} um)", b.kf, b.uy_um);
  std::string out = fmt::format("model truth {{ {}  maxwell m (k = {:.4g} N/mm, tau = {:.4g} ms)  {}", spring, b.km, b.tau_ms, friction);
  if (h == Hidden::column) {
    const double k1 = random.uniform(0.3, 0.6) * b.k, fr = f_mid * random.uniform(0.8, 1.25), zeta = random.uniform(0.1, 0.25);
    const double mass = k1 * 1e3 / std::pow(2.0 * std::numbers::pi * fr, 2);  // kg
    const double c = 2.0 * zeta * std::sqrt(k1 * 1e3 * mass) * 1e-3;          // N*s/mm
    out += fmt::format("  series c {{ spring k1 (k = {:.4g} N/mm)  parallel y {{ inerter b (b = {:.4g} kg)  dashpot d (c = {:.4g} N*s/mm) }} }}",
                       k1, mass, c);
  }
  if (h == Hidden::play)
    out += fmt::format("  series b {{ gap g (width = {:.4g} mm, center = {:.4g} mm)  spring k (k = {:.4g} N/mm) }}",
                       random.uniform(0.3, 0.6) * a_max, random.uniform(-0.12, 0.12) * a_max, random.uniform(1.0, 2.5) * b.k);
  if (h == Hidden::capped_maxwell)
    out += fmt::format("  series cm {{ slider cap (fy = {:.4g} N)  maxwell arm (k = {:.4g} N/mm, tau = {:.4g} ms) }}",
                       random.uniform(0.15, 0.3) * b.k * a_max, random.uniform(1.0, 2.0) * b.k,
                       1e3 / (2.0 * std::numbers::pi * f_mid) * random.uniform(0.5, 2.0));
  return out + " }";
}

inline std::string start_without(Hidden h) {
  std::string out = "model start {\n  spring s (k = 500 N/mm in [10, 10000])\n";
  if (h != Hidden::maxwell) out += "  maxwell m (k = 100 N/mm in [1, 10000], tau = 10 ms in [0.01, 10000])\n";
  if (h != Hidden::friction) out += "  friction f (k = 100 N/mm in [1, 10000], uy = 20 um in [0.1, 10000])\n";
  return out + "}\n";
}

// Noise of one draw (see the head of the file).
struct NoiseDraw {
  double s = 0.01;
  bool of_force = false;    // harmonic: force-amplitude noise; history: relative to |F|
  double phase_deg = 0.15;  // harmonic; 0: none
  double hetero = 0.0;      // the SD grows to (1 + hetero) times towards the smallest amplitude
  bool heavy = false;
  std::string text(bool history) const {
    const char* kind = history ? (of_force ? "force-relative" : "absolute") : (of_force ? "force-amplitude" : "K-relative");
    const std::string phase = history ? "" : phase_deg > 0.0 ? fmt::format(", phase {:.2g} deg", phase_deg) : ", no phase noise";
    return fmt::format("{} {:.2g} %{}{}{}", kind, 100.0 * s, phase,
                       hetero > 0.0 ? fmt::format(", heteroscedastic x{:.2g}", 1.0 + hetero) : std::string(), heavy ? ", t5 tails" : "");
  }
};

inline NoiseDraw draw_noise(PortableRandom& random, bool history) {
  NoiseDraw n;
  n.s = history ? random.uniform(0.002, 0.006) : random.uniform(0.005, 0.02);
  n.of_force = random.unit() < 0.5;
  n.phase_deg = random.unit() < 0.2 ? 0.0 : random.uniform(0.05, 0.3);
  n.hetero = random.unit() < 0.5 ? random.uniform(0.5, 1.5) : 0.0;
  n.heavy = random.unit() < 0.4;
  return n;
}

inline double hetero_factor(const NoiseDraw& n, double a, double a_min, double a_max) {
  if (n.hetero == 0.0 || a_max <= a_min) return 1.0;
  return 1.0 + n.hetero * std::log(a_max / a) / std::log(a_max / a_min);
}

inline BaseValues draw_base(PortableRandom& random) {
  return {random.uniform(200.0, 800.0), random.uniform(60.0, 300.0), random.uniform(2.0, 40.0), random.uniform(100.0, 400.0),
          random.uniform(20.0, 100.0)};
}

// A harmonic grid (Hidden split_yield, even_spring and capped_maxwell need histories: they are
// drawn as none here).
inline Scenario harmonic_scenario(unsigned seed, Hidden hidden) {
  PortableRandom random(seed * 7919u + 17u);
  const BaseValues base = draw_base(random);
  const std::vector<double> amplitudes = uneven_levels(random, 4 + static_cast<int>(random.unit() * 5), 0.03, random.uniform(1.0, 3.0));
  const std::vector<double> frequencies = uneven_levels(random, 4 + static_cast<int>(random.unit() * 6), random.uniform(0.5, 2.0),
                                                        random.uniform(30.0, 60.0));
  const double drop = random.unit() < 0.5 ? random.uniform(0.0, 0.15) : 0.0;
  const NoiseDraw noise = draw_noise(random, false);
  const double f_mid = std::sqrt(frequencies.front() * frequencies.back());
  Scenario sc;
  sc.truth = truth_with(base, hidden, random, amplitudes.back(), f_mid);
  sc.start = start_without(hidden);
  sc.description = fmt::format("harmonic {}x{} grid ({:.0f} % dropped), {}", amplitudes.size(), frequencies.size(), 100.0 * drop, noise.text(false));
  const runtime::Network network = network_from(sc.truth, "truth");
  const auto points = runtime::simulate_harmonic_grid(network, amplitudes, frequencies, simulation_options());
  double k_ref = 0.0;
  for (const auto& p : points) k_ref += std::log(p.measures.stiffness);
  k_ref = std::exp(k_ref / static_cast<double>(points.size()));
  const double a_ref = std::sqrt(amplitudes.front() * amplitudes.back());
  runtime::HarmonicData d;
  d.path = "generated.csv";
  double sum_k = 0.0, sum_p = 0.0, sum_floor = 0.0;
  for (const auto& p : points) {
    if (random.unit() < drop) continue;
    const double h = hetero_factor(noise, p.amplitude, amplitudes.front(), amplitudes.back());
    const double s_k = h * (noise.of_force ? 0.4 * noise.s * k_ref * a_ref / (p.measures.stiffness * p.amplitude) : noise.s);
    const double s_p = h * noise.phase_deg * std::numbers::pi / 180.0;
    d.amplitude.push_back(p.amplitude), d.frequency.push_back(p.frequency);
    d.stiffness.push_back(p.measures.stiffness * (1.0 + s_k * unit_noise(random, noise.heavy)));
    d.phase.push_back(p.measures.phase + s_p * unit_noise(random, noise.heavy));
    d.rows.push_back(static_cast<int>(d.rows.size()) + 2);
    const double cot = 1.0 / std::tan(p.measures.phase);
    sum_k += s_k * s_k, sum_p += s_p * s_p, sum_floor += s_k * s_k + s_p * s_p * cot * cot + 0.5 * std::pow(s_p, 4);
  }
  const double n = static_cast<double>(d.size());
  sc.stiffness = std::sqrt(sum_k / n), sc.phase = std::sqrt(sum_p / n), sc.floor = std::sqrt(sum_floor) / n;
  sc.data.push_back({d.path, 1.0, d});
  return sc;
}

// History files (Hidden column is drawn as none here: a resonance needs frequencies around it).
// CORRELATION: the noise's lag-1 autocorrelation rho, an AR(1) process of the same variance
// (e_j = rho e_j-1 + sqrt(1 - rho^2) z_j; a rig's anti-aliasing filter correlates its samples);
// 0: independent samples, the draws as without it.
inline Scenario history_scenario(unsigned seed, Hidden hidden, double correlation = 0.0) {
  PortableRandom random(seed * 104729u + 5u);
  const BaseValues base = draw_base(random);
  const int files = 1 + static_cast<int>(random.unit() * 3);
  const double a_max = random.uniform(0.8, 2.5);
  std::vector<double> amplitudes{a_max};
  for (int k = 1 + static_cast<int>(random.unit() * 2); k > 0; --k) amplitudes.push_back(amplitudes.back() * random.uniform(0.2, 0.6));
  const int cycles = 2 + static_cast<int>(random.unit() * 3), steps = 4 * (20 + static_cast<int>(random.unit() * 81));
  const bool triangles = random.unit() < 0.3;
  std::vector<double> rates;  // Hz (sines) or mm/s (triangles)
  double rate = triangles ? random.uniform(0.05, 0.5) : random.uniform(0.1, 1.0);
  for (int k = 0; k < files; ++k) rates.push_back(rate), rate *= random.uniform(3.0, 10.0);
  const NoiseDraw noise = draw_noise(random, true);
  const double f_mid = triangles ? rates.front() / (4.0 * a_max) : std::sqrt(rates.front() * rates.back());
  Scenario sc;
  const Hidden in_network = hidden == Hidden::column || hidden == Hidden::offset ? Hidden::none : hidden;
  sc.truth = truth_with(base, in_network, random, a_max, f_mid);
  sc.start = start_without(in_network);
  sc.description = fmt::format("{} file(s) of {} at {:.3g}..{:.3g} {}, {} cycles x {} samples, {} amplitudes, {}", files,
                               triangles ? "triangles" : "sines", rates.front(), rates.back(), triangles ? "mm/s" : "Hz", cycles, steps,
                               amplitudes.size(), noise.text(true));
  const runtime::Network network = network_from(sc.truth, "truth");
  double sum = 0.0;
  for (double r : rates) {
    const runtime::Drive drive = triangles ? runtime::static_triangle(amplitudes, r, cycles, steps)
                                           : runtime::quasistatic_sine(amplitudes, r, cycles, steps);
    const runtime::History h = runtime::run_history(network, drive, false, runtime::SolverChoice::fixed);
    double scale = 0.0;
    for (double f : h.force) scale = std::max(scale, std::abs(f));
    runtime::HistoryData d;
    d.path = fmt::format("generated_{}.csv", sc.data.size() + 1);
    d.drive = drive;
    double file_sum = 0.0, colored = 0.0;
    for (std::size_t j = 0; j < h.force.size(); ++j) {
      const double u = std::abs(drive.displacement[j]);
      const double sd = hetero_factor(noise, std::max(u, amplitudes.back()), amplitudes.back(), a_max) *
                        (noise.of_force ? noise.s * (0.2 * scale + std::abs(h.force[j])) : noise.s * scale);
      const double z = unit_noise(random, noise.heavy);
      colored = j == 0 ? z : correlation * colored + std::sqrt(1.0 - correlation * correlation) * z;
      d.force.push_back(h.force[j] + sd * colored), d.rows.push_back(static_cast<int>(d.rows.size()) + 2);
      file_sum += sd * sd;
    }
    if (hidden == Hidden::offset) {
      const double offset = (random.unit() < 0.5 ? -1.0 : 1.0) * random.uniform(0.02, 0.1) * scale;
      for (double& f : d.force) f += offset;
      sc.offsets.push_back(offset);
    }
    for (double f : d.force) d.force_scale = std::max(d.force_scale, std::abs(f));
    sum += file_sum / static_cast<double>(d.force.size()) / (d.force_scale * d.force_scale);
    sc.data.push_back({d.path, 1.0, d});
  }
  sc.force = std::sqrt(sum / static_cast<double>(files));
  return sc;
}

}  // namespace rheo::test::generated
