// Root elements of a fitted model written back as .rheo statements at the network's values, for
// the candidates of rheo diagnose that rebuild an element rather than add one beside it (free
// play in front of it, its yield made one-sided), and those candidates' trial families: the element's own names (so its parameters
// keep their paths), every free parameter with its own bounds, every fixed one as a value.
#pragma once

#include "runtime/diagnosis/trial.hpp"
#include "runtime/network/network.hpp"

#include <optional>
#include <string>
#include <vector>

namespace rheo::runtime::diagnosis {

struct ElementText {
  std::vector<std::string> lines;  // one per leaf; blocks open and close on lines of their own, children indented by two
  int free = 0;                    // free parameters written with bounds
  int symmetric_caps = 0;          // friction elements and sliders with one cap both ways
};

// With SPLIT != 0, every friction element and slider with one cap fy both ways is written
// with fy_pos = fy (1 + SPLIT) and fy_neg = fy (1 - SPLIT), free within the cap's bounds where
// it was free, else within [fy/1000, 1000 fy] (SPLIT in (-1, 1)). Nothing for an element that
// cannot be written so (a quadratic dashpot, Bouc-Wen or springpot in it, or a parameter that is
// neither given nor the alternative of one: a model-level parameter reference).
std::optional<ElementText> element_text(const Network& network, const lang::Element& element, double split = 0.0);

// The lines joined with newlines (for a probe model or a replacement).
std::string joined(const ElementText& text);

// The root element NAME of NETWORK's model; std::logic_error when there is none.
const lang::Element& root_element(const Network& network, const std::string& name);

// The centres of free play the backlash trials take, in half widths: centred and off-centre
// by half a half width either way; with SYMMETRIC_DRIVES (screen.hpp DataScales) and a
// mirror-symmetric element behind the play, not the negative one (its mirror image scores alike).
std::vector<double> play_biases(bool symmetric_drives);

// The gapped_element trials (trial.hpp): free play of each half width, at play_biases, in front
// of each root spring, Maxwell or friction element (a compliant member the play's series chain
// needs). Play in front of a friction element with one-sided caps is tried off-centre both ways
// (it is not its own mirror image).
std::vector<Trial> gapped_element_family(const Network& network, const std::vector<double>& half_widths, bool symmetric_drives);

// The one_sided_element trials: each root element holding friction elements or sliders with
// one cap both ways, their caps split by -0.5, -0.2, 0.2 and 0.5 (the screen refines the split).
std::vector<Trial> one_sided_family(const Network& network);

}  // namespace rheo::runtime::diagnosis
