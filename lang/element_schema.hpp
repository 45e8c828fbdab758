// Built-in element kinds: their parameters, dimensions and slot layout (see model.hpp).
#pragma once

#include "lang/model.hpp"

#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rheo::lang {

struct ParameterSpec {
  std::string_view name;  // "k"
  Dimension dimension;
  bool positive;                                           // value must be > 0
  std::string_view quantity;                               // "stiffness", for messages
  std::optional<double> default_value = std::nullopt;      // internal units; absent: required
  double below = std::numeric_limits<double>::infinity();  // value must be < below
};

struct ElementSpec {
  std::string_view kind;  // "maxwell"
  ElementKind element_kind;
  std::vector<ParameterSpec> slots;  // in slot order
  // Optional alternative for the last slot: given instead of it, the slot is derived as
  // slots[0] * alternative (maxwell: c = k * tau; friction: fy = k * uy). Exactly one of the
  // two must be given.
  std::vector<ParameterSpec> alternative;
  // Optional one-sided split of the last slot: the two given together instead of it (and of
  // its alternative), the last slot takes split[0] and a slot split[1] is appended (friction,
  // slider: fy_pos and fy_neg, the yield forces in tension and in compression).
  std::vector<ParameterSpec> split;
};

inline const std::vector<ElementSpec>& element_specs() {
  static const std::vector<ElementSpec> specs{
      {"spring", ElementKind::spring, {{"k", dim::stiffness, true, "stiffness"}}, {}, {}},
      {"yeoh",
       ElementKind::yeoh,
       {{"D10", dim::stiffness, true, "coefficient"}, {"D20", {1, -3, 0}, false, "coefficient"}, {"D30", {1, -5, 0}, false, "coefficient"}},
       {},
       {}},
      {"dashpot", ElementKind::dashpot, {{"c", dim::damping, true, "damping"}}, {}, {}},
      {"maxwell",
       ElementKind::maxwell,
       {{"k", dim::stiffness, true, "stiffness"}, {"c", dim::damping, true, "damping"}},
       {{"tau", dim::time, true, "time constant"}},
       {}},
      {"friction",
       ElementKind::friction,
       {{"k", dim::stiffness, true, "stiffness"}, {"fy", dim::force, true, "yield force"}},
       {{"uy", dim::length, true, "yield displacement"}},
       {{"fy_pos", dim::force, true, "yield force in tension"}, {"fy_neg", dim::force, true, "yield force in compression"}}},
      {"slider",
       ElementKind::slider,
       {{"fy", dim::force, true, "yield force"}},
       {},
       {{"fy_pos", dim::force, true, "yield force in tension"}, {"fy_neg", dim::force, true, "yield force in compression"}}},
      {"inerter", ElementKind::inerter, {{"b", dim::mass, true, "inertance"}}, {}, {}},
      {"quadratic_dashpot", ElementKind::quadratic_dashpot, {{"cq", dim::quadratic_damping, true, "quadratic damping"}}, {}, {}},
      {"gap", ElementKind::gap, {{"width", dim::length, true, "width"}, {"center", dim::length, false, "centre of the play", 0.0}}, {}, {}},
      {"poly_spring",
       ElementKind::poly_spring,
       {{"k1", dim::stiffness, true, "linear coefficient"},
        {"k2", {1, -2, 0}, false, "quadratic coefficient", 0.0},
        {"k3", {1, -3, 0}, false, "cubic coefficient", 0.0}},
       {},
       {}},
      {"bouc_wen",
       ElementKind::bouc_wen,
       {{"k", dim::stiffness, true, "stiffness"}, {"n", dim::none, true, "loop-shape exponent"}, {"fy", dim::force, true, "yield force"}},
       {{"uy", dim::length, true, "yield displacement"}},
       {}},
      {"springpot",
       ElementKind::springpot,
       {{"k", dim::stiffness, true, "stiffness"},
        {"alpha", dim::none, true, "fractional order", std::nullopt, 1.0},
        {"tau", dim::time, true, "time constant"},
        {"f_low", dim::frequency, true, "lower band limit", 0.01},
        {"f_high", dim::frequency, true, "upper band limit", 1000.0}},
       {},
       {}},
  };
  return specs;
}

inline const ElementSpec* find_element_spec(std::string_view kind) {
  for (const auto& s : element_specs())
    if (s.kind == kind) return &s;
  return nullptr;
}

}  // namespace rheo::lang
