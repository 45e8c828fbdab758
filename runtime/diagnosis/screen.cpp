#include "runtime/diagnosis/screen.hpp"

#include "lang/frontend.hpp"
#include "runtime/diagnosis/added_objective.hpp"
#include "runtime/diagnosis/element_text.hpp"
#include "runtime/fit/fit_scoring.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <optional>
#include <stdexcept>
#include <numbers>
#include <numeric>

namespace rheo::runtime::diagnosis {
namespace {

using Complex = std::complex<double>;

std::vector<double> log_spaced(double lo, double hi, int count) {
  std::vector<double> v;
  for (int i = 0; i < count; ++i) v.push_back(count == 1 ? std::sqrt(lo * hi) : lo * std::pow(hi / lo, static_cast<double>(i) / (count - 1)));
  return v;
}

// |u| at every turning point of a history's displacement.
std::vector<double> turning_amplitudes(const std::vector<double>& u) {
  std::vector<double> out;
  for (std::size_t k = 1; k + 1 < u.size(); ++k)
    if ((u[k] - u[k - 1]) * (u[k + 1] - u[k]) < 0.0 && std::abs(u[k]) > 0.0) out.push_back(std::abs(u[k]));
  if (!u.empty()) out.push_back(std::abs(u.back()) > 0.0 ? std::abs(u.back()) : std::abs(*std::max_element(u.begin(), u.end())));
  return out;
}

// The response of STATEMENT (one or more element lines) alone on every data set.
Signature simulate_statement(const std::string& statement, const std::vector<FitDataSet>& data, const ScoreSettings& score) {
  const lang::Program program = lang::compile_source("<diagnose probe>", "model probe {\n" + statement + "\n}\n");
  const Network network = Network::compile(program.models.front());
  Signature s;
  for (const auto& set : data) {
    const Prediction p = predict(network, set, FitMethod::exact, score.harmonic, nullptr, Offsets::none);  // the trial's force alone
    std::vector<Complex> k;
    for (const auto& point : p.points) k.push_back(std::polar(point.measures.stiffness, point.measures.phase));
    s.harmonic.push_back(std::move(k));
    s.history.push_back(p.force);
  }
  return s;
}

// The largest share of its stiffness k that a trial simulated at k = 1 (SIGNATURE) shows on DATA:
// max |K*_c| over harmonic points, max |s| / max |u| over histories; within [1e-3, 1] (a
// trial that never engages is sized as one fully engaged: its size then does not matter).
double engaged_share(const Signature& signature, const std::vector<FitDataSet>& data) {
  double share = 0.0;
  for (std::size_t f = 0; f < data.size(); ++f) {
    for (const Complex& k : signature.harmonic[f]) share = std::max(share, std::abs(k));
    if (data[f].is_harmonic()) continue;
    double u_max = 0.0, s_max = 0.0;
    for (double u : data[f].history().drive.displacement) u_max = std::max(u_max, std::abs(u));
    for (double s : signature.history[f]) s_max = std::max(s_max, std::abs(s));
    if (u_max > 0.0) share = std::max(share, s_max / u_max);
  }
  return share > 0.0 ? std::clamp(share, 1e-3, 1.0) : 1.0;
}

Signature simulate_alone(const Trial& trial, const std::vector<FitDataSet>& data, const ScoreSettings& score, const BoundScales& bounds) {
  std::string text;
  for (const auto& line : trial_statement(trial, "added", bounds)) text += line + "\n";
  return simulate_statement(text, data, score);
}


// argmin over [lo, hi] of a unimodal-enough g: a scan of `count` points (log-spaced when lo > 0),
// then a golden section between the best point's neighbours.
template <class G>
double minimise_1d(const G& g, double lo, double hi, int count, bool logarithmic) {
  std::vector<double> x(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    const double t = static_cast<double>(i) / (count - 1);
    x[static_cast<std::size_t>(i)] = logarithmic ? lo * std::pow(hi / lo, t) : lo + (hi - lo) * t;
  }
  std::size_t best = 0;
  double best_value = g(x[0]);
  for (std::size_t i = 1; i < x.size(); ++i)
    if (const double v = g(x[i]); v < best_value) best = i, best_value = v;
  double a = x[best == 0 ? 0 : best - 1], b = x[std::min(best + 1, x.size() - 1)];
  const double phi = (std::sqrt(5.0) - 1.0) / 2.0;
  double c = b - phi * (b - a), d = a + phi * (b - a), gc = g(c), gd = g(d);
  for (int it = 0; it < 40; ++it) {
    if (gc < gd) b = d, d = c, gd = gc, c = b - phi * (b - a), gc = g(c);
    else a = c, c = d, gc = gd, d = a + phi * (b - a), gd = g(d);
  }
  const double golden = gc < gd ? c : d;
  return std::min(gc, gd) < best_value ? golden : x[best];
}

struct RootSpring {
  std::string name;  // empty: none
  double k = 0.0;    // [N/mm]
  bool has_yeoh = false;
};

RootSpring stiffest_root_spring(const Network& network) {
  RootSpring out;
  for (const auto& e : network.model().root.children) {
    if (e.kind == lang::ElementKind::yeoh) out.has_yeoh = true;
    if (e.kind == lang::ElementKind::spring && network.parameter(e.parameters[0]) > out.k) {
      out.k = network.parameter(e.parameters[0]);
      out.name = e.name;
    }
  }
  return out;
}

// The location parameters of a shape: what the pattern search moves.
std::vector<double Trial::*> location_fields(Shape shape) {
  switch (shape) {
    case Shape::maxwell: return {&Trial::time};
    case Shape::friction: return {&Trial::slip};
    case Shape::capped_maxwell: return {&Trial::time, &Trial::slip};
    case Shape::capped_column: return {&Trial::frequency, &Trial::slip, &Trial::damping_ratio};
    case Shape::tuned_column: return {&Trial::frequency, &Trial::damping_ratio};
    case Shape::mass:
    case Shape::yeoh:
    case Shape::even_spring: return {};
    case Shape::asymmetric_friction:
    case Shape::gapped_spring: return {&Trial::slip};
    case Shape::gapped_element: return {&Trial::slip, &Trial::bias};
    case Shape::one_sided_element: return {&Trial::bias};
    case Shape::force_offset: return {};
  }
  return {};
}


// k2 of an even_spring trial (F = k1 u + k2 u^2) on the objective; returns that objective. The
// even part adds nothing to a harmonic point's measures where the odd part sets the extrema
// (max F - min F, K*_1): its signature there is zero, and harmonic data leave k2 at 0.
double size_even_spring(Trial& trial, const AddedObjective& objective, const std::vector<FitDataSet>& data, const DataScales& scales,
                        const RootSpring& root_spring) {
  Signature square;
  for (const auto& set : data) {
    std::vector<Complex> k;
    std::vector<double> s;
    if (set.is_harmonic()) k.assign(set.harmonic().size(), Complex{0.0, 0.0});
    else
      for (double u : set.history().drive.displacement) s.push_back(u * u);
    square.harmonic.push_back(k), square.history.push_back(s);
  }
  trial.stiffness = root_spring.name.empty() ? 0.02 * scales.bounds.stiffness : root_spring.k;
  const double range = std::max(trial.stiffness, scales.bounds.stiffness) / scales.bounds.max_displacement;
  trial.k2 = minimise_1d([&](double x) { return objective({&square}, {x}); }, -range, range, 41, false);
  return objective({&square}, {trial.k2});
}

// The offset c of a force_offset trial: m = F + c on every history whose offset is not fitted
// already (a constant signature there, zero elsewhere: harmonic measures do not see a constant
// force), c within +-max|F_exp|; returns the objective there.
double size_force_offset(Trial& trial, const AddedObjective& objective, const std::vector<FitDataSet>& data) {
  Signature constant;
  double range = 0.0;
  for (const auto& set : data) {
    constant.harmonic.emplace_back(set.is_harmonic() ? set.harmonic().size() : 0, Complex{0.0, 0.0});
    constant.history.emplace_back(set.is_harmonic() ? 0 : set.history().force.size(), set.is_harmonic() || set.force_offset.free ? 0.0 : 1.0);
    if (!set.is_harmonic() && !set.force_offset.free) range = std::max(range, set.history().force_scale);
  }
  trial.stiffness = minimise_1d([&](double c) { return objective({&constant}, {c}); }, -range, range, 41, false);
  return objective({&constant}, {trial.stiffness});
}

// D20 and D30 of a yeoh trial by coordinate descent on the objective; returns that objective.
double size_yeoh(Trial& trial, const AddedObjective& objective, const std::vector<FitDataSet>& data, const DataScales& scales,
                 const RootSpring& root_spring) {
  // Basis responses of D20 = 1 and D30 = 1 (unit-free polynomials, not elements).
  Signature cubic, quintic;
  for (const auto& set : data) {
    std::vector<Complex> k3, k5;
    std::vector<double> s3, s5;
    if (set.is_harmonic())
      for (double a : set.harmonic().amplitude) k3.emplace_back(4.0 * a * a), k5.emplace_back(6.0 * std::pow(a, 4));
    else
      for (double u : set.history().drive.displacement) s3.push_back(4.0 * u * u * u), s5.push_back(6.0 * std::pow(u, 5));
    cubic.harmonic.push_back(k3), quintic.harmonic.push_back(k5), cubic.history.push_back(s3), quintic.history.push_back(s5);
  }
  const double u = scales.bounds.max_displacement, d10 = scales.bounds.stiffness / 2.0;  // the range of eq. 3.3's terms
  double d20 = 0.0, d30 = 0.0;
  for (int sweep = 0; sweep < 4; ++sweep) {
    d20 = minimise_1d([&](double x) { return objective({&cubic, &quintic}, {x, d30}); }, -d10 / (u * u), 5.0 * d10 / (u * u), 41, false);
    d30 = minimise_1d([&](double x) { return objective({&cubic, &quintic}, {d20, x}); }, 0.0, 5.0 * d10 / std::pow(u, 4), 41, false);
  }
  trial.d20 = d20, trial.d30 = d30;
  trial.stiffness = root_spring.name.empty() ? 0.02 * scales.bounds.stiffness : root_spring.k;
  return objective({&cubic, &quintic}, {d20, d30});
}

}  // namespace

DataScales data_scales(const std::vector<FitDataSet>& data) {
  std::vector<double> f, a, stiffness;
  double max_u = 0.0;
  for (const auto& set : data) {
    if (set.is_harmonic()) {
      const HarmonicData& h = set.harmonic();
      f.insert(f.end(), h.frequency.begin(), h.frequency.end());
      a.insert(a.end(), h.amplitude.begin(), h.amplitude.end());
      stiffness.insert(stiffness.end(), h.stiffness.begin(), h.stiffness.end());
      max_u = std::max(max_u, *std::max_element(h.amplitude.begin(), h.amplitude.end()));
      continue;
    }
    const HistoryData& h = set.history();
    const auto& u = h.drive.displacement;
    const auto& t = h.drive.time;
    double umax = 0.0, vmax = 0.0;
    for (std::size_t k = 1; k < u.size(); ++k) {
      umax = std::max(umax, std::abs(u[k]));
      vmax = std::max(vmax, std::abs(u[k] - u[k - 1]) / (t[k] - t[k - 1]));
    }
    const double rate = umax > 0.0 ? vmax / (2.0 * std::numbers::pi * umax) : 1.0;  // a sine's frequency of that speed
    f.push_back(rate / 10.0);
    f.push_back(rate * 10.0);
    for (double turning : turning_amplitudes(u)) a.push_back(turning);
    stiffness.push_back(umax > 0.0 ? h.force_scale / umax : 1.0);
    max_u = std::max(max_u, umax);
  }
  DataScales s;
  auto positive = [](std::vector<double>& v) { std::erase_if(v, [](double x) { return !(x > 0.0) || !std::isfinite(x); }); };
  positive(f), positive(a), positive(stiffness);
  if (!f.empty()) s.frequency_low = *std::min_element(f.begin(), f.end()), s.frequency_high = *std::max_element(f.begin(), f.end());
  if (!a.empty()) s.amplitude_low = *std::min_element(a.begin(), a.end()), s.amplitude_high = *std::max_element(a.begin(), a.end());
  if (!stiffness.empty()) {
    std::nth_element(stiffness.begin(), stiffness.begin() + static_cast<std::ptrdiff_t>(stiffness.size() / 2), stiffness.end());
    s.bounds.stiffness = stiffness[stiffness.size() / 2];
  }
  s.bounds.max_displacement = max_u > 0.0 ? max_u : 1.0;
  s.has_history = std::any_of(data.begin(), data.end(), [](const FitDataSet& set) { return !set.is_harmonic(); });
  s.fixed_offsets = static_cast<int>(
      std::count_if(data.begin(), data.end(), [](const FitDataSet& set) { return !set.is_harmonic() && !set.force_offset.free; }));
  s.symmetric_drives = std::all_of(data.begin(), data.end(), [](const FitDataSet& set) {
    return set.is_harmonic() && std::all_of(set.harmonic().preload.begin(), set.harmonic().preload.end(), [](double p) { return p == 0.0; });
  });
  return s;
}

std::vector<Trial> trial_family(Effect effect, const DataScales& s, const std::string& root_spring) {
  std::vector<Trial> family;
  const double two_pi = 2.0 * std::numbers::pi;
  auto add = [&](Shape shape, double time, double slip, double frequency, double zeta) {
    Trial t;
    t.effect = effect, t.shape = shape, t.time = time, t.slip = slip, t.frequency = frequency, t.damping_ratio = zeta;
    family.push_back(t);
  };
  switch (effect) {
    case Effect::rate_dependence:
      for (double f : log_spaced(s.frequency_low / 3.0, s.frequency_high * 3.0, 10)) add(Shape::maxwell, 1.0 / (two_pi * f), 0.0, 0.0, 0.0);
      break;
    case Effect::amplitude_dependence:
      for (double uy : log_spaced(s.amplitude_low / 30.0, s.amplitude_high, 8)) add(Shape::friction, 0.0, uy, 0.0, 0.0);
      break;
    case Effect::coupled_amplitude_frequency:
      for (double f : log_spaced(s.frequency_low, s.frequency_high, 5))
        for (double slip : log_spaced(s.amplitude_low / 10.0, s.amplitude_high, 4)) {
          add(Shape::capped_maxwell, 1.0 / (two_pi * f), slip, 0.0, 0.0);
          add(Shape::capped_column, 0.0, slip, f, 0.3);
        }
      break;
    case Effect::inertia:
      for (double f : log_spaced(s.frequency_low, s.frequency_high, 10))
        for (double zeta : {0.15, 0.5}) add(Shape::tuned_column, 0.0, 0.0, f, zeta);
      add(Shape::mass, 0.0, 0.0, s.frequency_high, 0.0);
      break;
    case Effect::nonlinear_elasticity: {
      add(Shape::yeoh, 0.0, 0.0, 0.0, 0.0);
      family.back().replaces = root_spring;
      break;
    }
    case Effect::asymmetry:  // one-sided yield forces show in histories only (see trial.hpp)
      add(Shape::even_spring, 0.0, 0.0, 0.0, 0.0);
      family.back().replaces = root_spring;
      if (s.has_history)
        for (double uy : log_spaced(s.amplitude_low / 30.0, s.amplitude_high, 6))
          for (double bias : {-0.5, 0.5}) {
            add(Shape::asymmetric_friction, 0.0, uy, 0.0, 0.0);
            family.back().bias = bias;
          }
      break;
    case Effect::backlash:
      for (double half : log_spaced(s.amplitude_low / 10.0, s.amplitude_high, 6))
        for (double bias : play_biases(s.symmetric_drives)) {
          add(Shape::gapped_spring, 0.0, half, 0.0, 0.0);
          family.back().bias = bias;
        }
      break;
    case Effect::offset:
      if (s.fixed_offsets > 0) {
        add(Shape::force_offset, 0.0, 0.0, 0.0, 0.0);
        family.back().offsets = s.fixed_offsets;
      }
      break;
    case Effect::none: break;
  }
  return family;
}

std::vector<ScreenedEffect> screen(const FitResult& fit, const std::vector<FitDataSet>& data, const ScoreSettings& score, double parsimony) {
  const DataScales scales = data_scales(data);
  const AddedObjective objective(fit, data, score);
  const double base = objective({}, {});
  const RootSpring root_spring = stiffest_root_spring(fit.network);
  const double k_max = 3.0 * scales.bounds.stiffness, k_min = 1e-4 * scales.bounds.stiffness;
  // Sizes TRIAL (its stiffness, or D20 and D30) for the least objective and returns that objective.
  // The response of a root element alone (gapped_element: what the play is put in front of).
  std::map<std::string, Signature> element_alone;
  auto size_trial = [&](Trial& trial) {
    if (trial.shape == Shape::gapped_element || trial.shape == Shape::one_sided_element) {
      // The rebuilt element replaces the element's response s_e by its own, s_p, resized:
      // F_m - s_e + a s_p (the element's force scales with a, as every shape's with its
      // stiffness), a within a decade either side of 1.
      const lang::Element& e = root_element(fit.network, trial.replaces);
      if (trial.shape == Shape::one_sided_element) trial.inner = joined(*element_text(fit.network, e, trial.bias));
      auto known = element_alone.find(trial.replaces);
      if (known == element_alone.end())
        known = element_alone.emplace(trial.replaces, simulate_statement(joined(*element_text(fit.network, e)), data, score)).first;
      const Signature played = simulate_alone(trial, data, score, scales.bounds);
      const Signature* basis_pair[] = {&played, &known->second};
      const std::vector<const Signature*> basis(std::begin(basis_pair), std::end(basis_pair));
      trial.stiffness = minimise_1d([&](double a) { return objective(basis, {a, -1.0}); }, 0.1, 10.0, 21, true);
      return objective(basis, {trial.stiffness, -1.0});
    }
    if (trial.shape == Shape::yeoh) return size_yeoh(trial, objective, data, scales, root_spring);
    if (trial.shape == Shape::even_spring) return size_even_spring(trial, objective, data, scales, root_spring);
    if (trial.shape == Shape::force_offset) return size_force_offset(trial, objective, data);
    trial.stiffness = 1.0;  // the signature is per unit stiffness; a refined trial arrives sized
    const Signature s = simulate_alone(trial, data, score, scales.bounds);
    // A spring behind play adds k g at its most engaged point, g = engaged_share(s) <= 1 (g -> 0
    // as the play's half-width nears the largest amplitude): the range bounds that added stiffness.
    const double per_k = trial.shape == Shape::gapped_spring ? engaged_share(s, data) : 1.0;
    trial.stiffness = minimise_1d([&](double a) { return objective({&s}, {a}); }, k_min / per_k, k_max / per_k, 30, true);
    return objective({&s}, {trial.stiffness});
  };
  std::vector<ScreenedEffect> out;
  for (Effect effect : kEffects) {
    if (effect == Effect::nonlinear_elasticity && root_spring.has_yeoh) continue;
    if (effect == Effect::asymmetry && !scales.has_history) continue;     // harmonic measures do not see it
    if (effect == Effect::offset && scales.fixed_offsets == 0) continue;  // no history, or every offset fitted already
    ScreenedEffect best;
    best.effect = effect;
    best.gain = -1.0;
    // Scan the family; then refine the best member of each shape by a pattern search over its
    // location (times, slips, resonances and damping ratios), halving the step in log each round.
    std::vector<std::pair<Trial, double>> best_of_shape;
    std::vector<Trial> family = trial_family(effect, scales, root_spring.name);
    const std::vector<Trial> rebuilt = effect == Effect::backlash
                                           ? gapped_element_family(fit.network, log_spaced(scales.amplitude_low / 10.0, scales.amplitude_high, 6),
                                                                   scales.symmetric_drives)
                                       : effect == Effect::asymmetry ? one_sided_family(fit.network)
                                                                     : std::vector<Trial>{};
    family.insert(family.end(), rebuilt.begin(), rebuilt.end());
    for (Trial trial : family) {
      ++best.trials;
      const double value = size_trial(trial);
      auto it = std::find_if(best_of_shape.begin(), best_of_shape.end(), [&](const auto& b) { return b.first.shape == trial.shape; });
      if (it == best_of_shape.end()) best_of_shape.emplace_back(trial, value);
      else if (value < it->second) *it = {trial, value};
    }
    for (auto& [trial, value] : best_of_shape) {
      double step = 2.0;
      for (int round = 0; round < 3; ++round, step = std::sqrt(step))
        for (double Trial::*field : location_fields(trial.shape))
          for (double factor : {step, 1.0 / step}) {
            Trial moved = trial;
            moved.*field *= factor;
            if (field == &Trial::damping_ratio && moved.damping_ratio > 2.0) continue;
            if (field == &Trial::bias && std::abs(moved.bias) >= 0.95) continue;  // the rest position stays in the play
            ++best.trials;
            if (const double v = size_trial(moved); v < value) trial = moved, value = v;
          }
      const double gain = base > 0.0 ? std::max(0.0, 1.0 - value / base) : 0.0;
      if (gain > best.gain) best.gain = gain, best.trial = trial;
    }
    // What the best leaves, and the shape with the fewest parameters (of those, the lowest
    // objective) that leaves at most (1 + parsimony)^2 of it.
    const double best_left = (1.0 - best.gain) * base, margin = (1.0 + parsimony) * (1.0 + parsimony);
    double simpler_left = 0.0;
    for (const auto& [trial, value] : best_of_shape) {
      const int count = added_parameter_count(trial), fewest = added_parameter_count(best.simpler ? *best.simpler : best.trial);
      if (value <= margin * best_left && (count < fewest || (best.simpler && count == fewest && value < simpler_left)))
        best.simpler = trial, simpler_left = value;
    }
    if (best.simpler) best.simpler_gain = base > 0.0 ? std::max(0.0, 1.0 - simpler_left / base) : 0.0;
    out.push_back(best);
  }
  std::stable_sort(out.begin(), out.end(), [](const ScreenedEffect& a, const ScreenedEffect& b) { return a.gain > b.gain; });
  return out;
}

}  // namespace rheo::runtime::diagnosis
