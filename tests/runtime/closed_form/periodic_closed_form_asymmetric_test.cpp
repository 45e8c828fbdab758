// The closed-form periodic state of laws that are not odd (issue 24): a poly_spring's even
// power and one-sided yield forces in the model's parallel body, against dense numeric
// integration of the law and against the independent time-stepping and IDA paths; nested, with
// off-centre gaps, they take the event path over the whole period (pwl_periodic.hpp).
#include "runtime/closed_form/periodic_closed_form.hpp"
#include "runtime/closed_form/pwl_branch.hpp"
#include "runtime/network/leaf_kernels.hpp"
#include "runtime/protocols/harmonic.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace periodic_closed_form_asymmetric_test {

using namespace rheo;
using runtime::HarmonicDefinition;
using runtime::HarmonicOptions;
using runtime::SteadyState;

namespace {

runtime::HarmonicPoint stepped(const runtime::Network& net, double u0, double f, HarmonicDefinition definition, int steps, double preload = 0.0) {
  HarmonicOptions options;
  options.definition = definition;
  options.steady_state = SteadyState::time_stepping;
  options.steps_per_cycle = steps;
  return runtime::simulate_harmonic_point(net, u0, f, options, preload);
}

void check_limit(const runtime::Network& net, double u0, double f, HarmonicDefinition definition, double preload = 0.0) {
  const auto exact = runtime::closed_form_harmonic_point(net, u0, f, definition, preload);
  const auto coarse = stepped(net, u0, f, definition, 2048, preload);
  const auto fine = stepped(net, u0, f, definition, 16384, preload);
  CAPTURE(u0);
  CAPTURE(f);
  CAPTURE(preload);
  CHECK(exact.cycles == 0);
  CHECK(test::relative_error(coarse.measures.stiffness, exact.measures.stiffness) < 5e-6);
  CHECK(std::abs(coarse.measures.phase - exact.measures.phase) < 5e-6);
  CHECK(test::relative_error(fine.measures.stiffness, exact.measures.stiffness) < 1e-7);
  CHECK(std::abs(fine.measures.phase - exact.measures.phase) < 1e-7);
}

}  // namespace

TEST_CASE("one-sided friction and slider and a poly_spring in the body: the closed form is the limit of time stepping") {
  const auto net = test::network_from(R"(
    model asym {
      spring      e (k = 50)
      poly_spring p (k1 = 30 N/mm, k2 = 8 N/mm^2, k3 = 1.5 N/mm^3)
      friction    f (k = 400 N/mm, fy_pos = 13 N, fy_neg = 20 N)
      slider      s (fy_pos = 2 N, fy_neg = 5 N)
      maxwell     m (k = 80, tau = 2 ms)
      dashpot     d (c = 0.4 N*s/mm)
    })",
                                      "asym");
  REQUIRE(runtime::has_closed_form_periodic_state(net));
  // The dashpot makes time stepping sample the force at step midpoints (a force that jumps with
  // the rate), where the slider's jump at a turning point leaves no O(1/N) error.
  for (auto definition : {HarmonicDefinition::thesis, HarmonicDefinition::first_harmonic})
    for (double u0 : {0.02, 0.5, 2.0})  // 0.02 mm: the friction element never slips (2 k u0 < fy_pos + fy_neg)
      for (double f : {1.0, 30.0}) check_limit(net, u0, f, definition);
  check_limit(net, 0.5, 5.0, HarmonicDefinition::thesis, 0.7);  // about a preload: P(p + u) - P(p)
}

TEST_CASE("a friction element whose shake-down from rest slips once: K = k, no loss, as time stepping finds") {
  // k u0 = 16 N > fy_pos = 13 N but 2 k u0 = 32 N < fy_pos + fy_neg = 33 N: it slips on the first
  // peak, then stays elastic about an offset.
  const auto net = test::network_from("model f { spring e (k = 10)  friction f (k = 400 N/mm, fy_pos = 13 N, fy_neg = 20 N) }", "f");
  const auto exact = runtime::closed_form_harmonic_point(net, 0.04, 2.0, HarmonicDefinition::thesis);
  CHECK(exact.measures.stiffness == doctest::Approx(410.0).epsilon(1e-13));
  CHECK(exact.measures.phase == 0.0);
  const auto steps = stepped(net, 0.04, 2.0, HarmonicDefinition::thesis, 2048);
  CHECK(steps.measures.stiffness == doctest::Approx(410.0).epsilon(1e-9));
  CHECK(std::abs(steps.measures.phase) < 1e-9);
}

TEST_CASE("a poly_spring alone: (max F - min F)/2 and the first harmonic against dense numeric integration of its law") {
  const runtime::PolyLaw law{20.0, -6.0, 0.8};
  const auto net = test::network_from("model p { poly_spring p (k1 = 20 N/mm, k2 = -6 N/mm^2, k3 = 0.8 N/mm^3) }", "p");
  for (double u0 : {0.3, 1.5, 4.0}) {
    const int m = 200000;
    double f_max = -1e300, f_min = 1e300, in_phase = 0.0, quadrature = 0.0;
    for (int j = 0; j < m; ++j) {
      const double theta = 2.0 * std::numbers::pi * j / m, f = law.force(u0 * std::sin(theta));
      f_max = std::max(f_max, f), f_min = std::min(f_min, f);
      in_phase += f * std::sin(theta), quadrature += f * std::cos(theta);
    }
    const double storage = 2.0 * in_phase / (m * u0), loss = 2.0 * quadrature / (m * u0);  // (1/(pi u0)) int F e^{i theta}
    const auto first = runtime::closed_form_harmonic_point(net, u0, 3.0, HarmonicDefinition::first_harmonic);
    const auto thesis = runtime::closed_form_harmonic_point(net, u0, 3.0, HarmonicDefinition::thesis);
    CAPTURE(u0);
    CHECK(first.measures.storage == doctest::Approx(storage).epsilon(1e-9));
    CHECK(std::abs(loss) < 1e-9 * storage);
    CHECK(first.measures.storage == doctest::Approx(20.0 + 0.75 * 0.8 * u0 * u0).epsilon(1e-13));
    CHECK(thesis.measures.force_amplitude == doctest::Approx(0.5 * (f_max - f_min)).epsilon(1e-8));
    // The even part breaks max F = -min F: F^ is not the force at +u0.
    CHECK(std::abs(thesis.measures.force_amplitude - law.force(u0)) > 0.1 * 6.0 * u0 * u0);
  }
}

TEST_CASE("nested one-sided caps and off-centre gaps take the event path over the whole period, and IDA agrees") {
  runtime::PwlBranch branch;
  const auto symmetric = test::network_from("model n { spring k0 (k = 10)  series c { spring a (k = 300)  friction f (k = 600, fy = 40 N) } }", "n");
  REQUIRE(runtime::PwlBranch::build(symmetric, symmetric.topology().subtrees[0], branch));
  CHECK(branch.odd);
  const auto one_sided = test::network_from(
      "model n { spring k0 (k = 10)  series c { spring a (k = 300)  friction f (k = 600, fy_pos = 40 N, fy_neg = 25 N) } }", "n");
  REQUIRE(runtime::PwlBranch::build(one_sided, one_sided.topology().subtrees[0], branch));
  CHECK_FALSE(branch.odd);
  const runtime::PwlEdge& slider = branch.edges[static_cast<std::size_t>(branch.switches[0])];
  CHECK(slider.value == 40.0);
  CHECK(slider.cap_neg == 25.0);
  CHECK(slider.slip_force(-1) == -25.0);
  const auto centred = test::network_from("model g { series c { gap g (width = 0.4 mm)  spring a (k = 300) }  maxwell m (k = 50, tau = 1 ms) }", "g");
  REQUIRE(runtime::PwlBranch::build(centred, centred.topology().subtrees[0], branch));
  CHECK(branch.odd);
  const auto offset = test::network_from(
      "model g { series c { gap g (width = 0.4 mm, center = 0.1 mm)  spring a (k = 300) }  maxwell m (k = 50, tau = 1 ms) }", "g");
  REQUIRE(runtime::PwlBranch::build(offset, offset.topology().subtrees[0], branch));
  CHECK_FALSE(branch.odd);
  CHECK(branch.edges[static_cast<std::size_t>(branch.switches[0])].center == 0.1);
  HarmonicOptions ida;
  ida.solver = runtime::SolverChoice::sundials;
  ida.tolerance = 1e-8;
  for (const auto* net : {&one_sided, &offset})
    for (double u0 : {0.05, 0.5, 2.0}) {
      CAPTURE(u0);
      const auto exact = runtime::try_closed_form_harmonic_point(*net, u0, 5.0, HarmonicDefinition::thesis);
      REQUIRE(exact.has_value());
      const auto b = runtime::simulate_harmonic_point(*net, u0, 5.0, ida);
      CHECK(b.converged);
      CHECK(test::relative_error(exact->measures.stiffness, b.measures.stiffness) < 1e-5);
      CHECK(std::abs(exact->measures.phase - b.measures.phase) < 1e-5);
    }
  // The off-centre gap's loop is not half-wave symmetric: its stiffness differs from the centred one's.
  const auto c = runtime::closed_form_harmonic_point(centred, 0.25, 5.0, HarmonicDefinition::thesis);
  const auto o = runtime::closed_form_harmonic_point(offset, 0.25, 5.0, HarmonicDefinition::thesis);
  CHECK(test::relative_error(o.measures.stiffness, c.measures.stiffness) > 0.05);
}

}  // namespace periodic_closed_form_asymmetric_test
