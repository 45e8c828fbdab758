// Internals shared by the translation units of DaeIntegrator (dae_integrator.cpp: set-up,
// residuals and stepping; dae_events.cpp: mode switches and restarts). Not for other users.
#pragma once

#include "runtime/dae/dae_integrator.hpp"
#include "runtime/dae/sundials_owners.hpp"

#include <cstddef>
#include <vector>

namespace rheo::runtime {

// A stuck slider slips when |F| exceeds fy (1 + kSlack) and stays stuck after a velocity reversal
// while |F| <= fy (1 + kSlack/2); the margin keeps the switch from chattering on roundoff at the
// instant of reversal, where |F| = fy. A gap closes when |e| exceeds w/2 (1 + kGapSlack).
inline constexpr double kSlack = 1e-6;
inline constexpr double kGapSlack = 1e-9;

struct DaeIntegrator::Solver {
  sundials::Context context;
  sundials::Vector y, yp, id, tolerance;
  sundials::Matrix jacobian;
  sundials::LinearSolver linear_solver;
  sundials::IdaMemory ida;
};

// Element I of V, for the int indices the graph and the layout use.
template <class T>
T& at(std::vector<T>& v, int i) {
  return v[static_cast<std::size_t>(i)];
}
template <class T>
const T& at(const std::vector<T>& v, int i) {
  return v[static_cast<std::size_t>(i)];
}

}  // namespace rheo::runtime
