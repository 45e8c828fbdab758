// The physical effects `rheo diagnose` names (docs/cli.md "rheo diagnose"); the strings are
// part of the interface (report and JSON).
#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace rheo::runtime::diagnosis {

enum class Effect {
  amplitude_dependence,         // rate-independent (friction) damping is missing
  rate_dependence,              // a relaxation time is missing
  nonlinear_elasticity,         // stiffening or softening at large displacement
  coupled_amplitude_frequency,  // amplitude and frequency dependence do not separate (thesis ch. 9)
  inertia,                      // a resonance: stiffness rising above its trend, a phase peak
  asymmetry,                    // a law that is not odd: yield or stiffness differ in tension and compression
  backlash,                     // free play, possibly off-centre, before a branch engages
  offset,                       // a constant force the measured history carries (a load cell's zero): the data line's force_offset
  none,                         // the residual is at the noise level
};

inline constexpr std::array<Effect, 8> kEffects{Effect::amplitude_dependence,
                                                Effect::rate_dependence,
                                                Effect::nonlinear_elasticity,
                                                Effect::coupled_amplitude_frequency,
                                                Effect::inertia,
                                                Effect::asymmetry,
                                                Effect::backlash,
                                                Effect::offset};

constexpr std::string_view effect_name(Effect effect) {
  switch (effect) {
    case Effect::amplitude_dependence: return "amplitude-dependence";
    case Effect::rate_dependence: return "rate-dependence";
    case Effect::nonlinear_elasticity: return "nonlinear-elasticity";
    case Effect::coupled_amplitude_frequency: return "coupled-amplitude-frequency";
    case Effect::inertia: return "inertia";
    case Effect::asymmetry: return "asymmetry";
    case Effect::backlash: return "backlash";
    case Effect::offset: return "offset";
    case Effect::none: return "none";
  }
  return "none";
}

inline std::optional<Effect> effect_named(std::string_view name) {
  for (Effect e : kEffects)
    if (effect_name(e) == name) return e;
  if (name == "none") return Effect::none;
  return std::nullopt;
}

}  // namespace rheo::runtime::diagnosis
