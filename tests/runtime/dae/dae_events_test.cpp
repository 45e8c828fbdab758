// DaeIntegrator's events (dae_events.cpp): restarts where sliders switch, against fixed steps at
// fine steps on the differential test's two-tone drive (two_tone_reference.hpp).
#include "runtime/dae/dae_protocols.hpp"
#include "support.hpp"
#include "two_tone_reference.hpp"

#include <doctest/doctest.h>

namespace dae_events_test {

using namespace rheo;

// Differential seed 41, model 71: the friction element's slider and the 9.49 N slider beside the
// dashpot slip together and stop together, 20 us after the drive reverses at t = 31 ms. IDA found
// the friction element's root; the other slider, stuck there, carried 8e-5 N beyond its yield force
// (its dashpot's force at the rate the root left) and slipped again, now with its rate's stale
// sign, so its root was missed and it slipped the wrong way until the next sample: 8.9 N (0.45 of
// max |F|) off at t = 32 ms. Observed now 2e-4 of max |F| (the fixed steps' switch inside a step).
TEST_CASE("two sliders that stop together after a reversal (differential seed 41, model 71): fixed steps' forces") {
  const auto network = test::network_from(R"(model m {
series {
maxwell (k = 9125.5 N/mm, c = 17.1779 N*s/mm)
spring (k = 10626.9 N/mm)
parallel {
friction (k = 36.4885 N/mm, uy = 56.8724 um)
slider (fy = 9.49481 N)
dashpot (c = 0.290865 N*s/mm)
}
}
})",
                                          "m");
  const double gap = test::gap_to_extrapolated_fixed_steps(network, runtime::dae_history(network, test::two_tone_drive(1), false).force);
  MESSAGE("IDA against fixed steps: ", gap, " of max |F|");
  CHECK(gap < 1e-3);
}

// Differential seed 53, model 106: a gap in series with two stiff polynomial springs (a friction
// element beside the second) closes on its compression stop in the first cycle from rest; IDA's
// root found the contact with the gap's force, from IDACalcIC, at a rounding residue of tension,
// and the gap opened again beyond its stop, where no root was left to close it: no force for that
// half cycle, and the cycle-to-cycle check passed on it, so K was 991 N/mm against fixed steps'
// 1831 (0.3 mm, 2 Hz). A closed gap under tension opens now only if it is still under tension
// after the step of rates_ahead. Observed now: the same K as extrapolated fixed steps, d within 1.1e-6.
TEST_CASE("a gap that closes on its compression stop from rest stays closed (differential seed 53, model 106): fixed steps' K") {
  const auto network = test::network_from(R"(model m {
series {
poly_spring (k1 = 4897.22 N/mm, k2 = 288.62 N/mm^2, k3 = 9.7442 N/mm^3)
gap (width = 0.014271 mm, center = -0.00330309 mm)
parallel {
poly_spring (k1 = 3008.68 N/mm, k2 = 1879.54 N/mm^2, k3 = 1402.84 N/mm^3)
friction (k = 195.586 N/mm, fy = 0.521524 N)
}
}
})",
                                          "m");
  const auto [ida, gap] = test::ida_point_against_fixed_steps(network, 0.3, 2.0);
  REQUIRE(ida.converged);
  MESSAGE("IDA against fixed steps: K ", gap.stiffness, ", d ", gap.damping);
  CHECK(gap.stiffness < 1e-4);
  CHECK(gap.damping < 1e-4);
}

// Differential seed 53, model 191: a friction element (1.74 N) before a 55870 N/mm spring beside a
// quadratic dashpot. Where it starts to slip its force drops by kSlack fy, and the stiff spring
// relaxes through the dashpot, near zero rate, in about 1e-9 s: IDA's corrector cut its first step
// to 1e-12 s, and the slip rate it read there crossed zero. The slider stuck, reached
// fy (1 + kSlack) 1.4e-8 s later and slipped again: 3000 events in 0.02 ms (42000 and 33 s of CPU
// once its force had IDA's default Newton share). A slip root now stands only where the slip
// rate over the next 1e-3 of the time horizon (a backward-Euler step) reverses; otherwise that
// step passes the transient. Observed: 6 events, 1.8e-7 of max |F| from extrapolated fixed steps.
TEST_CASE("a friction element that starts to slip beside a stiff spring and a quadratic dashpot (differential seed 53, model 191)") {
  const auto network = test::network_from(R"(model m {
series {
spring (k = 10.0844 N/mm)
parallel {
quadratic_dashpot (cq = 0.00826331 N*s^2/mm^2)
series {
dashpot (c = 3.97937 N*s/mm)
parallel {
dashpot (c = 0.652055 N*s/mm)
series {
friction (k = 818.636 N/mm, fy = 1.74084 N)
parallel {
spring (k = 4.43904 N/mm)
spring (k = 55870.3 N/mm)
quadratic_dashpot (cq = 0.000505469 N*s^2/mm^2)
}
}
}
}
}
}
series {
yeoh (D10 = 2.03023 N/mm, D20 = -1.13104 N/mm^3, D30 = 0.481886 N/mm^5)
parallel {
spring (k = 20.1798 N/mm)
yeoh (D10 = 10.438 N/mm, D20 = 0 N/mm^3, D30 = 0 N/mm^5)
}
}
springpot (k = 5.8134 N/mm, alpha = 0.857213, tau = 35.7898 ms, f_low = 1 Hz, f_high = 100 Hz)
}
)",
                                          "m");
  runtime::DaeStatistics statistics;
  const double gap = test::gap_to_extrapolated_fixed_steps(network, runtime::dae_history(network, test::two_tone_drive(1), false, &statistics).force);
  MESSAGE("IDA against fixed steps: ", gap, " of max |F|; ", statistics.events, " events");
  CHECK(statistics.events < 100);
  CHECK(gap < 1e-4);
}

}  // namespace dae_events_test
