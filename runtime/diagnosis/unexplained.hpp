// The shape of a residual that is more than the noise (noise_estimate.hpp): where it lies and
// what it resembles, for the verdict `unexplained` (diagnose.hpp), when no candidate element
// removes it. People read it to choose an element the vocabulary lacks.
//
// Harmonic tables: the terms r_K^2 + r_d^2 of err (6.1) summed per amplitude level and per
// frequency level; the narrowest run of adjacent levels holding at least half of the sum, in
// each direction (a miss spread evenly spans every level).
// Histories: the force residual r = F - F_exp over every file, projected on one signal at a
// time; the signal of the largest share (r.s)^2 / (s.s r.r) is what it resembles:
//   constant        an offset (a force at rest, a load cell's zero)
//   u^2             a law that is not odd (different in tension and compression)
//   u               a stiffness
//   u^3             stiffening or softening
//   sign(du/dt)     a yield force (friction)
//   du/dt           a viscous force
#pragma once

#include "runtime/fit/fit.hpp"

#include <optional>
#include <string_view>
#include <vector>

namespace rheo::runtime::diagnosis {

enum class Resemblance { offset, even_law, stiffness, cubic, yield_force, viscous };

constexpr std::string_view resemblance_name(Resemblance r) {
  switch (r) {
    case Resemblance::offset: return "a constant force offset";
    case Resemblance::even_law: return "a force law that is not odd (different in tension and compression)";
    case Resemblance::stiffness: return "a stiffness (force proportional to displacement)";
    case Resemblance::cubic: return "stiffening or softening (force in u^3)";
    case Resemblance::yield_force: return "a yield force (friction: a force that flips with the direction of motion)";
    case Resemblance::viscous: return "a viscous force (proportional to velocity)";
  }
  return "";
}

struct LevelRange {
  double low = 0.0, high = 0.0;  // [mm] or [Hz]
  double share = 0.0;            // of the squared residual held there
  int levels = 0, of = 0;        // levels in the range, of all measured
};

struct ResidualShape {
  std::optional<LevelRange> amplitudes, frequencies;  // harmonic
  std::optional<Resemblance> resembles;               // histories
  double resembles_share = 0.0;                       // its share of the squared force residual
};

// FIT: the model fitted to DATA.
ResidualShape residual_shape(const FitResult& fit, const std::vector<FitDataSet>& data);

}  // namespace rheo::runtime::diagnosis
