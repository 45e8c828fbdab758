// A point-local cold start of the event path's shooting (pwl_periodic.hpp) for an odd branch
// with one slider: the first harmonic of its periodic state by a describing function.
//
// With the slider's elongation e prescribed, the rest of the branch is linear; in phasors
// (x(t) = Im(x^ e^{i w t}), the drive u^ = u0) its node equilibrium with the slider as a
// constraint of elongation e^ (multiplier: the slider's tension F^) is
//   [K(w) r; r^T 0] [x^; F^] = [f u^; e^ - rho u^],   K(w) = K - w^2 M + i w C,
// so F^ = F_stuck u^ - Z e^, Z the stiffness the slider sees with the terminal held and F_stuck
// its tension when rigid. Replacing Z by a spring |Z| makes the slider a Jenkins element driven
// by v^ = F_stuck u^ / Z, whose periodic slip is known exactly (amplitude a = |v^|, yield
// y = fy/|Z|: stuck from the turning point until v has moved by 2 y, then slipping with
// s = v - y); its first harmonic s^ is the describing function's estimate of e^, and the node
// phasors from the system above give the start X0 = (Im x^, w Re x^) at t = 0.
//
// Where |F_stuck u0| <= fy the slider never reaches its cap: no start is given (the stuck
// linear state is then the periodic state itself). The start is a function of the point's
// drive (u0, w) and the branch's values only: nothing of other points enters it.
#pragma once

#include "runtime/closed_form/pwl_mode.hpp"

namespace rheo::runtime {

// The estimate above into X0 (2 N entries: positions [mm], velocities [mm/s]); false where
// it is not given: the branch has no slider, more than one, a gap or uneven caps, the slider
// would not slip, or the constrained system is singular.
bool pwl_describing_start(const PwlBranch& branch, double u0, double omega, PwlVector& X0);

}  // namespace rheo::runtime
