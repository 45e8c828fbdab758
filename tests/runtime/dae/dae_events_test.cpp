// DaeIntegrator's events (dae_events.cpp): restarts where sliders switch, against fixed steps at
// fine steps on the differential test's two-tone drive (two_tone_reference.hpp).
#include "runtime/dae/dae_protocols.hpp"
#include "support.hpp"
#include "two_tone_reference.hpp"

#include <doctest/doctest.h>

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
