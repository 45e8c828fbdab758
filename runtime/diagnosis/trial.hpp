// The elements `rheo diagnose` adds, one shape per way of supplying a missing effect, and their
// .rheo statements. Every shape's force is proportional to its `stiffness` k at fixed `time`,
// `slip`, `frequency` and `damping_ratio` (all its force parameters scale with k), so the
// screening (screen.hpp) sizes a shape by one factor.                   [N, mm, s; b in kg]
//   maxwell         maxwell (k, tau)                         rate-dependence (eq. 2.3)
//   friction        friction (k, uy)                         amplitude-dependence (eq. 2.9)
//   capped_maxwell  series { slider (fy = k slip); maxwell (k, tau) }
//                                                            coupled-amplitude-frequency: the series
//                                                            friction-viscous branch of Fig. 9.1
//   capped_column   series { slider (fy = k slip); spring (k); parallel { inerter (b); dashpot (c) } }
//                                                            coupled-amplitude-frequency with a
//                                                            resonance (a hydrobushing's fluid column)
//   tuned_column    series { spring (k); parallel { inerter (b); dashpot (c) } }
//                                                            inertia: K*(w) = 1/(1/k + 1/(i w c - b w^2)),
//                                                            resonance at b = k/(2 pi f_r)^2,
//                                                            c = 2 zeta sqrt(k b)
//   mass            inerter (b = k/(2 pi f)^2)               inertia: a mass the drive moves (the part's,
//                                                            or the rig's not subtracted), K*(w) = -b w^2,
//                                                            sized by its stiffness k at the highest
//                                                            measured frequency f
//   yeoh            yeoh (D10, D20, D30) (eq. 3.3)           nonlinear-elasticity: replaces the root
//                                                            spring `replaces` (D10 = k/2) or, when
//                                                            there is none, is added (D10 = k/2 small)
//   asymmetric_friction  friction (k, fy_pos = k slip (1 + bias), fy_neg = k slip (1 - bias))
//                                                            asymmetry: a yield force that differs in
//                                                            tension and compression
//   even_spring     poly_spring (k1, k2)                     asymmetry: F = k1 u + k2 u^2; replaces the
//                                                            root spring `replaces` (k1 = k) or is added
//                                                            (k1 = k small)
//   gapped_spring   series { gap (width = 2 slip, center = bias slip); spring (k) }
//                                                            backlash: a spring engaged after free play
//                                                            whose centre is offset by bias half-widths
//   gapped_element  series { gap (width = 2 slip, center = bias slip); <the root element `replaces`> }
//                                                            backlash: free play in series with the
//                                                            branch it frees (`inner`: that element's
//                                                            statement at its fitted values; `stiffness`
//                                                            the factor its force took in the screen,
//                                                            the refit starting from it as fitted)
//   one_sided_element  <the root element `replaces`, its caps fy split into fy_pos = fy (1 + bias),
//                      fy_neg = fy (1 - bias)>           asymmetry: yield forces of the model's own
//                                                            friction elements and sliders that differ
//                                                            in tension and compression (`inner`: the
//                                                            rewritten statement, `stiffness` as above)
#pragma once

#include "runtime/diagnosis/effect.hpp"

#include <string>
#include <vector>

namespace rheo::runtime::diagnosis {

enum class Shape {
  maxwell,
  friction,
  capped_maxwell,
  capped_column,
  tuned_column,
  mass,
  yeoh,
  asymmetric_friction,
  even_spring,
  gapped_spring,
  gapped_element,
  one_sided_element,
  force_offset
};

struct Trial {
  Effect effect = Effect::none;
  Shape shape = Shape::maxwell;
  double stiffness = 1.0;      // k [N/mm]; force_offset: the offset c [N]
  double time = 0.0;           // tau [s]
  double slip = 0.0;           // uy, or fy/k of a slider [mm]
  double frequency = 0.0;      // f_r [Hz]
  double damping_ratio = 0.0;  // zeta [-]
  double d20 = 0.0;            // yeoh [N/mm^3]
  double d30 = 0.0;            // yeoh [N/mm^5]
  double bias = 0.0;           // asymmetric_friction, gapped_spring, gapped_element, one_sided_element [-], in (-1, 1)
  double k2 = 0.0;             // even_spring [N/mm^2]
  double bulge = 0.0;          // capped_column: the chamber walls' stiffness k_b [N/mm] beside the column's mass and channel (0: none)
  std::string replaces;        // yeoh, even_spring: the root spring it replaces; empty: added;
                               // gapped_element, one_sided_element: the root element it rebuilds
  std::string inner;           // gapped_element, one_sided_element: the statement of `replaces` (lines), with bounds
  int split_parameters = 0;    // one_sided_element: the free parameters the split adds (1 per cap that was free, 2 per fixed one)
  int offsets = 0;             // force_offset: the histories whose offset it frees (one parameter each)
};

// Scales of the measurement that bound the added parameters.
struct BoundScales {
  double stiffness = 1.0;         // typical measured stiffness [N/mm]
  double max_displacement = 1.0;  // [mm]
};

// The statement of TRIAL named NAME, one line per element (none for a force_offset), with bounds on every parameter
// (wide, around the values, so that the refit can move them): k within [K/1e4, 10 K] of the
// measured stiffness, times, slips, inertances and damping within three decades either side,
// D20 within [-D, 5 D]/u^2 and D30 within [0, 5 D/u^4] for the largest displacement u, D the larger of
// D10 and half the measured stiffness; k2 within [-R, R]/u, R the larger of k1 and the measured
// stiffness; a gap's center within [-u, u] (a fitted center beyond half the width acts as the
// stop touching at rest).
std::vector<std::string> trial_statement(const Trial& trial, const std::string& name, const BoundScales& scales);

// One line for people: "a Maxwell element (k = 51.2 N/mm, tau = 3.2 ms)".
std::string trial_summary(const Trial& trial);

// Parameters the shape adds (a yeoh replacing a spring adds two, free play in front of an
// element its width and centre).
int added_parameter_count(const Trial& trial);

}  // namespace rheo::runtime::diagnosis
