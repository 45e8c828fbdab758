// Fixed points of the event path's cycle maps (pwl_periodic.hpp): the shooting Newton step
// of the one-cycle map X(0) -> X(T), which is affine for a fixed sequence of events,
// X -> J X + b with J its Jacobian and Y = J X0 + b one application of it from X0.
#pragma once

#include "runtime/closed_form/pwl_mode.hpp"

namespace rheo::runtime {

// The fixed point that iterating the map from X0 converges to: in the eigenvectors of J,
// xi_i = b_i / (1 - lambda_i), except along eigenvalues 1 (directions the map leaves where
// they are, such as the offset of a slider that never slips), where X0's component is kept.
// A least-squares solve of (J - I) X = -b where J's eigenvectors are too ill-conditioned.
PwlVector affine_fixed_point(const PwlMatrix& J, const PwlVector& X0, const PwlVector& Y);

// The same fixed point where no eigenvalue of J is 1 (no heap): the half-period map, on which
// a never-slipping slider's offset has eigenvalue -1. By LU (at the size 4, a slider-capped
// column's map, by the closed-form inverse) where J - I is well conditioned (reciprocal
// condition above 1e-8), else by complete orthogonal decomposition: where an
// eigenvalue is 1 all the same, the step is the least-norm solution of (J - I) dX = X0 - Y.
PwlVector least_norm_fixed_point(const PwlMatrix& J, const PwlVector& X0, const PwlVector& Y);

}  // namespace rheo::runtime
