// The start of a harmonic point's first cycle against the cycle it starts: where the start is
// the discrete periodic state (linear subtrees, capped chains whose caps hold), one simulated
// cycle must return to it up to rounding.
#include "runtime/stepping/periodic_start.hpp"

#include "runtime/protocols/harmonic.hpp"
#include "runtime/stepping/simulator.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace periodic_start_test {

using namespace rheo;

namespace {

struct CycleFromStart {
  runtime::State start, end;
};

// One cycle of u = u0 sin(w t) in n fixed steps from set_periodic_start's state.
CycleFromStart one_cycle(const runtime::Network& network, double amplitude, double frequency, int n) {
  const runtime::Simulator simulator(network);
  const double dt = 1.0 / (frequency * n);
  const runtime::StepPlan plan = runtime::StepPlan::make(network, dt);
  CycleFromStart c{simulator.rest_state(), {}};
  runtime::set_periodic_start(network, plan, amplitude, n, c.start);
  runtime::State state = c.start, next = state;
  for (int k = 1; k <= n; ++k) {
    simulator.step(plan, state, amplitude * std::sin(2.0 * std::numbers::pi * k / n), next);
    std::swap(state, next);
  }
  c.end = state;
  return c;
}

double largest_change(const CycleFromStart& c) {
  double change = 0.0;
  for (std::size_t i = 0; i < c.start.values.size(); ++i) change = std::max(change, std::abs(c.end.values[i] - c.start.values[i]));
  return change;
}

double largest_value(const runtime::State& s) {
  double v = 0.0;
  for (double x : s.values) v = std::max(v, std::abs(x));
  return v;
}

// A resonant fluid column (f_r = sqrt(k1/b)/2pi = 19.5 Hz) with a Maxwell arm and a series
// spring inside its parallel block: every kind the linearisation knows.
const std::string kColumn = R"(model m {
  spring s (k = 500 N/mm)
  series c {
    spring k1 (k = 300 N/mm)
    parallel y {
      inerter b (b = 20 kg)
      dashpot d (c = 1 N*s/mm)
      maxwell arm (k = 200 N/mm, tau = 4 ms)
      series bulge { spring k2 (k = 80 N/mm)  spring k3 (k = 240 N/mm) }
    }
  }
})";

const std::string kCapped = R"(model m {
  spring rubber (k = 800 N/mm)
  series fluid {
    slider cap (fy = 50 N)
    friction f (k = 2000 N/mm, fy = 80 N)
    spring chamber (k = 500 N/mm)
    parallel y { inerter column (b = 30 kg)  dashpot channel (c = 2 N*s/mm)  spring bulge (k = 200 N/mm) }
  }
})";

}  // namespace

TEST_CASE("periodic start: a linear subtree starts at its discrete periodic state, below, at and above resonance") {
  const auto network = test::network_from(kColumn, "m");
  for (double frequency : {2.0, 19.5, 60.0}) {
    const CycleFromStart c = one_cycle(network, 0.4, frequency, 128);
    const double scale = largest_value(c.start);
    MESSAGE(frequency << " Hz: largest state change over the first cycle " << largest_change(c) << " of " << scale);
    CHECK(scale > 0.1);
    CHECK(largest_change(c) < 1e-11 * scale);
  }
  runtime::HarmonicOptions options;
  options.steady_state = runtime::SteadyState::time_stepping;
  options.solver = runtime::SolverChoice::fixed;
  options.steps_per_cycle = 128;
  const auto point = runtime::simulate_harmonic_point(network, 0.4, 19.5, options);
  CHECK(point.converged);
  CHECK(point.cycles == 2);  // nested networks always check a second cycle
}

TEST_CASE("periodic start: a slider-capped chain whose cap holds starts periodic, one that slips starts at rest") {
  const auto network = test::network_from(kCapped, "m");
  // At 0.05 mm and 5 Hz the chain force stays near k_chain u0 ~ 20 N < 50 N: the cap holds.
  const CycleFromStart held = one_cycle(network, 0.05, 5.0, 128);
  CHECK(largest_value(held.start) > 0.01);
  CHECK(largest_change(held) < 1e-11 * largest_value(held.start));
  // At 1 mm the chain would carry hundreds of N: the slider slips and the subtree starts at rest.
  const CycleFromStart slipped = one_cycle(network, 1.0, 5.0, 128);
  CHECK(largest_value(slipped.start) == 0.0);
  CHECK(largest_change(slipped) > 1e-3);
}

}  // namespace periodic_start_test
