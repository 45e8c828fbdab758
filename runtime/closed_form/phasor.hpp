// Complex dynamic stiffness K*(w) of a linear network (springs, dashpots, Maxwell elements,
// springpots and inerters in any series/parallel nesting), composed directly from the checked element tree:
//   spring k                      K* = k
//   dashpot c                     K* = i w c
//   inerter b                     K* = -b w^2
//   Maxwell k, tau = c/k          K* = k i w tau / (1 + i w tau)         (eq. 5.11, B.58)
//   springpot k, alpha, tau       K* = k (i w tau)^alpha                 (exact, not the chain
//                                 the integrators use: runtime/network/springpot.hpp)
//   parallel                      K* = sum K*_i                          (eq. 2.1, C.9)
//   series                        K* = 1 / sum (1 / K*_i)
// Independent of the compiler and the time-stepping kernels: a second path for the tests and
// an exact harmonic evaluation of linear models. K = |K*|, phase = arg K*.
#pragma once

#include "lang/model.hpp"

#include <complex>
#include <optional>
#include <vector>

namespace rheo::runtime {

// nullopt when the network holds a non-linear element (yeoh, friction, slider,
// quadratic_dashpot, gap, bouc_wen).
std::optional<std::complex<double>> complex_stiffness(const lang::CheckedModel& model, const std::vector<double>& parameter_values, double frequency);

}  // namespace rheo::runtime
