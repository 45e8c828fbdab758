// A candidate of rheo diagnose (diagnose.hpp, step 3) as a model: its element written into the
// fitted model's source under a name of its own, and what its refitted values say about a
// fluid column's resonance (whether the data resolve it, and its limit without inertia).
#pragma once

#include "runtime/diagnosis/screen.hpp"
#include "runtime/io/fit_data.hpp"
#include "runtime/network/network.hpp"

#include <optional>
#include <string>
#include <vector>

namespace rheo::runtime::diagnosis {

// Index of the parameter PATH of MODEL, or -1.
int parameter_index(const lang::CheckedModel& model, const std::string& path);

// A root element name for EFFECT's element not yet taken in MODEL: "slip", "slip2", ...
std::string candidate_name(const lang::CheckedModel& model, Effect effect);

// The fitted model's source with TRIAL written in as NAME, under COMMENT: appended to the
// model's body, or in place of the root element TRIAL.replaces (a gapped_element holds it).
std::string with_trial(const std::string& fitted_text, const lang::CheckedModel& fitted, const Trial& trial, const std::string& name,
                       const BoundScales& bounds, const std::string& comment);

// Empty when the resonance of a refitted fluid column (the element ELEMENT of MODEL;
// sqrt((k + k_b)/b) / (2 pi) with its walls' spring) lies inside the measured frequencies with a
// margin of 10 % either side, else why not. Shapes without a
// resonance are always resolved.
std::string resolved_resonance(const Trial& trial, const lang::CheckedModel& model, const Network& network, const std::string& element,
                               const DataScales& scales);

// NETWORK with every gap's centre within its play, |center| <= width/2: a fit may move a centre
// beyond half the width, where every path acts as if it were at +-width/2 (leaf_kernels.hpp
// gap_center), but a .rheo file refuses it. The same predictions, written as a file can state
// them (unless the edge lies outside the bounds the centre was fitted in: then it stays).
Network with_gaps_in_play(const Network& network);

// The limit without inertia (b -> 0) of a refitted slider-capped fluid column ELEMENT: chamber
// spring and channel dashpot in series are a Maxwell element of k = chamber.k and
// tau = channel.c / chamber.k, capped by the same slider: the capped_maxwell shape, one
// parameter fewer and no resonance to place.
Trial resonance_free_limit(const Trial& column, const lang::CheckedModel& model, const Network& refitted, const std::string& element);

// The way back: the slider-capped fluid column COLUMN (its shape and resonance f_r) started from
// the refitted limit ELEMENT (cap fy, arm k and tau): chamber k = arm.k, channel c = k tau, and
// the mass that puts the resonance at f_r, b = k/(2 pi f_r)^2 (so zeta = pi f_r tau). The column
// holds its limit (b -> 0), so a column refit that ends above its limit's gap stopped outside
// its basin; this is where to search it again.
Trial column_from_limit(const Trial& column, const lang::CheckedModel& model, const Network& refitted, const std::string& element);

// The limit tau -> infinity of a refitted slider-capped Maxwell arm ELEMENT (cap fy, arm k and
// tau): a slider in series with the arm's spring, which is a friction element of k = arm.k and
// uy = fy/k (eq. 2.9), one parameter fewer and named amplitude-dependence. An arm that hardly
// relaxes while it sticks (tau beyond longest_stick at its uy) gives the loops of this limit.
Trial friction_limit(const Trial& arm, const lang::CheckedModel& model, const Network& refitted, const std::string& element);

// Whether the refitted capped Maxwell arm ELEMENT of MODEL relaxes more slowly than the drives of
// DATA stick it: tau > longest_stick(data, fy/k) (below).
bool outlasts_sticking(const lang::CheckedModel& model, const Network& refitted, const std::string& element, const std::vector<FitDataSet>& data);

// REFITTED's values with the yield forces and stiffnesses of the capped Maxwell arm ELEMENT (cap
// fy, arm k; its tau kept) and of the root friction element FRICTION (k, fy, or k and uy = fy/k)
// exchanged; nullopt where one of the four is not free or FRICTION's yield is one-sided. A fit
// can end with the two in each other's roles: the friction element carrying a slow arm's cap
// (634 N/mm, 226 N for the arm's 654 N/mm, 234 N) and the arm the friction element's slip, a
// local minimum 3.9 times the noise; exchanged, the search reaches the truth.
std::optional<std::vector<double>> roles_exchanged(const lang::CheckedModel& model, const Network& refitted, const std::string& element,
                                                   const lang::Element& friction);

// The longest a friction element of slip UY [mm] sticks under the drives of DATA [s]: the time
// the drive takes from a turning point to move 2 uy away from it, where the force goes from one
// yield force to the other (eq. 2.9). A harmonic point of amplitude a > uy at frequency f:
// acos(1 - 2 uy/a) / (2 pi f); a history: from each turning point of its displacement, to the
// drive 2 uy away (linear between samples) before the next turning point. 0 where the drives never slip it.
double longest_stick(const std::vector<FitDataSet>& data, double uy);

// The refitted slider-capped fluid column ELEMENT (cap fy, chamber k, mass b, channel c; no
// walls' spring yet) with the chamber walls' compliance beside its mass and channel: a spring
// `bulge` from the column's node to ground, k_b started at kBulgeStart k (the refit moves it
// within the stiffness bounds). The column's node then rests on k + k_b, so the resonance
// sqrt((k + k_b)/b) / (2 pi) and the static stiffness behind the cap k k_b / (k + k_b) are set
// by two springs, not one: a stiffness the rubber's springs alone cannot carry at low
// frequency. The standard library's hydromount has it (k2).
inline constexpr double kBulgeStart = 0.5;
Trial bulged_column(const Trial& column, const lang::CheckedModel& model, const Network& refitted, const std::string& element);

}  // namespace rheo::runtime::diagnosis
