// The IDA harmonic point's start at the periodic state of the linearised network: the phasors of
// hand-solved networks, the networks it leaves to a start from rest, and harmonic points that
// settle in their first cycles where a start from rest took hundreds (a springpot's tail mode) or
// never settled (an undamped mass behind a stuck slider, reproducer 09 of issue 26).
#include "runtime/dae/dae_linear_start.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <numbers>

namespace dae_linear_start_test {

using namespace rheo;
using runtime::EdgeKind;

namespace {

runtime::DaeGraph graph_of(const char* source) { return runtime::DaeGraph::build(test::network_from(source, "m")); }

}  // namespace

TEST_CASE("a Maxwell element's linear periodic start is its phasor X = A k/(k + i w c) at t = 0") {
  const double k = 12.0, c = 0.3, amplitude = 0.7, omega = 2.0 * std::numbers::pi * 9.0;
  const auto graph = graph_of("model m { spring (k = 5 N/mm)\n maxwell (k = 12 N/mm, tau = 25 ms) }");
  const auto start = runtime::dae_linear_periodic_start(graph, amplitude, omega);
  REQUIRE(start);
  REQUIRE(start->positions.size() == 1);
  REQUIRE(start->rate_edge_rates.size() == 1);
  const std::complex<double> x = amplitude * k / std::complex<double>(k, omega * c);  // the node between spring and dashpot
  CHECK(start->positions[0] == doctest::Approx(x.imag()).epsilon(1e-12).scale(0.0));
  CHECK(start->rate_edge_rates[0] == doctest::Approx(omega * x.real()).epsilon(1e-12));  // the dashpot's elongation is the node's
  CHECK(x.imag() < -0.1);                                                                // far from rest at this phase
}

TEST_CASE("a stuck slider carries the drive to a mass on a spring: X2 = A k/(k - w^2 b)") {
  const double k = 115.086, b = 11.7486e-3, amplitude = 0.4, omega = 2.0 * std::numbers::pi * 2.0;  // N/mm, N s^2/mm
  const auto graph = graph_of(
      "model m { maxwell (k = 123.874 N/mm, tau = 20.4112 ms)\n series { slider (fy = 1.67762 N)\n"
      " series { spring (k = 115086 N/m)\n inerter (b = 11.7486 kg) } } }");
  const auto start = runtime::dae_linear_periodic_start(graph, amplitude, omega);
  REQUIRE(start);
  const double x2 = amplitude * k / (k - omega * omega * b);  // real: in phase with the drive
  int inerter_edges = 0;
  for (std::size_t r = 0; r < graph.rate_edges.size(); ++r) {
    const auto& edge = graph.edges[static_cast<std::size_t>(graph.rate_edges[r])];
    if (edge.kind != EdgeKind::inerter) continue;
    ++inerter_edges;
    CHECK(start->positions[static_cast<std::size_t>(edge.a)] == doctest::Approx(0.0).scale(amplitude).epsilon(1e-12));
    CHECK(start->rate_edge_rates[r] == doctest::Approx(omega * x2).epsilon(1e-12));
  }
  CHECK(inerter_edges == 1);
}

TEST_CASE("no linear start with a gap, a quadratic dashpot or a bouc_wen, or where no admittance holds a node") {
  CHECK_FALSE(runtime::dae_linear_periodic_start(graph_of("model m { spring (k = 1 N/mm)\n series { gap (width = 1 mm)\n spring (k = 2 N/mm) } }"),
                                                 1.0, 1.0));
  CHECK_FALSE(runtime::dae_linear_periodic_start(graph_of("model m { spring (k = 1 N/mm)\n quadratic_dashpot (cq = 1 N*s^2/mm^2) }"), 1.0, 1.0));
  CHECK_FALSE(runtime::dae_linear_periodic_start(graph_of("model m { spring (k = 1 N/mm)\n bouc_wen (k = 2 N/mm, fy = 1 N, n = 2) }"), 1.0, 1.0));
  // Two dashpots in series at w = 0: nothing holds the node between them.
  CHECK_FALSE(runtime::dae_linear_periodic_start(
      graph_of("model m { spring (k = 1 N/mm)\n series { dashpot (c = 1 N*s/mm)\n dashpot (c = 2 N*s/mm) } }"), 1.0, 0.0));
}

TEST_CASE("IDA harmonic points start at the linear periodic state: a springpot's chain settles at once, to its closed form") {
  const auto network = test::network_from(
      "model m { spring (k = 20 N/mm)\n springpot (k = 50 N/mm, alpha = 0.3, tau = 10 ms, f_low = 1 Hz, f_high = 100 Hz) }", "m");
  runtime::HarmonicOptions ida, exact;
  ida.definition = exact.definition = lang::HarmonicDefinition::first_harmonic;  // exact from samples
  ida.solver = runtime::SolverChoice::sundials;
  ida.steps_per_cycle = 256;
  ida.max_cycles = 4;  // from rest the tail mode (l_hi (1 + alpha)/alpha, about 21 s) took thousands of cycles
  exact.steady_state = runtime::SteadyState::closed_form;
  for (const double frequency : {2.0, 30.0}) {
    CAPTURE(frequency);
    const auto point = runtime::simulate_harmonic_point(network, 0.5, frequency, ida);
    const auto reference = runtime::simulate_harmonic_point(network, 0.5, frequency, exact);
    CHECK(point.converged);
    CHECK(point.cycles <= 3);
    CHECK(point.measures.stiffness == doctest::Approx(reference.measures.stiffness).epsilon(1e-6));
    CHECK(point.measures.phase == doctest::Approx(reference.measures.phase).epsilon(1e-5).scale(0.0));
  }
}

TEST_CASE("IDA harmonic point of an undamped mass behind a stuck slider (issue 26, reproducer 09) settles, as fixed steps do") {
  const auto network = test::network_from(
      "model m { maxwell (k = 123.874 N/mm, tau = 20.4112 ms)\n series { slider (fy = 1.67762 N)\n"
      " series { spring (k = 115086 N/m)\n inerter (b = 11.7486 kg) } } }",
      "m");
  runtime::HarmonicOptions ida, fixed;
  ida.definition = fixed.definition = lang::HarmonicDefinition::first_harmonic;  // exact from samples
  ida.solver = runtime::SolverChoice::sundials;
  ida.steps_per_cycle = 256;
  ida.max_cycles = 6;
  fixed.solver = runtime::SolverChoice::fixed;
  fixed.steady_state = runtime::SteadyState::time_stepping;
  fixed.steps_per_cycle = 8192;
  const auto point = runtime::simulate_harmonic_point(network, 0.4, 2.0, ida);
  const auto reference = runtime::simulate_harmonic_point(network, 0.4, 2.0, fixed);
  CHECK(point.converged);
  REQUIRE(reference.converged);
  CHECK(point.measures.stiffness == doctest::Approx(reference.measures.stiffness).epsilon(1e-5));
  CHECK(point.measures.phase == doctest::Approx(reference.measures.phase).epsilon(1e-4));
}

}  // namespace dae_linear_start_test
