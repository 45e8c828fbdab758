// Which free parameters the model's force is affine in, the others held: the force scales of the
// root parallel block.
//
// A branch of the root block adds its force to the others', and the force of each root element
// is linear in one scale when its shape is held:
//   spring k;  dashpot c;  slider fy;  yeoh D10, D20, D30 (each, eq. 3.3);
//   Maxwell k at fixed tau = c/k (c = k tau: F = k G(t; tau), eq. 2.7);
//   friction k at fixed uy = fy/k (fy = k uy: F = k G(t; uy), eq. 2.9);
//   springpot k at fixed alpha, tau, f_low, f_high (its Maxwell modes scale with it).
// So F(t) = F_0(t) + sum_j s_j G_j(t) for the scales s_j, and so are a history's forces and a
// harmonic point's first harmonic K*_1 (for a linear network also the thesis definition's K
// and phase, which equal |K*| and arg K*). Fitting uses this to solve the scales exactly
// (variable projection, separable_fit.hpp).
//
// Found from the compiled network, whatever the parameters' expressions: a parameter is a force
// scale when moving it changes only root-group coefficients, each affinely, keeping every
// Maxwell element's tau and friction element's uy, and no parameter of a nested branch.
#pragma once

#include "runtime/network/network.hpp"

#include <vector>

namespace rheo::runtime {

// The positions j in `free` (indices of model parameters) whose parameter is a force scale.
std::vector<int> force_scales(const Network& network, const std::vector<int>& free);

}  // namespace rheo::runtime
