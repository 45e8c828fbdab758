// A mode's build (pwl_mode.cpp) from the frequency-independent parts another frequency's build
// kept (PwlModeStructure: its products and the frame of A, X's maps and the tensions but for the
// drive's columns) against a build from scratch at the same frequency: every matrix,
// row and modal factor the same to the last bit, for every mode of branches that hold a mass,
// a damped massless node and an undamped one (static condensation), stuck and slipping.
#include "runtime/closed_form/pwl_mode.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

#include <numbers>
#include <string>
#include <vector>

namespace pwl_mode_test {

using namespace rheo;

namespace {

runtime::PwlBranch branch_of(const std::string& source) {
  const auto net = test::network_from(source, "m");
  runtime::PwlBranch branch;
  REQUIRE(runtime::PwlBranch::build(net, net.topology().subtrees[0], branch));
  return branch;
}

// Every mode code of BRANCH: each switch stuck/open (0) or at +1 or -1.
std::vector<runtime::PwlModeCode> every_code(const runtime::PwlBranch& branch) {
  std::vector<runtime::PwlModeCode> codes{runtime::PwlModeCode(branch.switches.size(), 0)};
  for (std::size_t s = 0; s < branch.switches.size(); ++s) {
    const std::size_t count = codes.size();
    for (std::size_t k = 0; k < count; ++k)
      for (std::int8_t state : {std::int8_t{1}, std::int8_t{-1}}) {
        runtime::PwlModeCode code = codes[k];
        code[s] = state;
        codes.push_back(code);
      }
  }
  return codes;
}

void check_same(const runtime::PwlModeSystem& a, const runtime::PwlModeSystem& b) {
  REQUIRE(a.dim == b.dim);
  CHECK(a.A == b.A);
  CHECK(a.to_X == b.to_X);
  CHECK(a.from_X == b.from_X);
  CHECK(a.held_drive == b.held_drive);
  CHECK(a.force == b.force);
  CHECK(a.force_rate == b.force_rate);
  CHECK(a.force_curvature == b.force_curvature);
  CHECK(a.guards == b.guards);
  CHECK(a.guard_rates == b.guard_rates);
  REQUIRE(a.transitions.size() == b.transitions.size());
  for (std::size_t i = 0; i < a.transitions.size(); ++i) {
    CHECK(a.transitions[i].which == b.transitions[i].which);
    CHECK(a.transitions[i].to == b.transitions[i].to);
    CHECK(a.transitions[i].scale == b.transitions[i].scale);
    CHECK(a.transitions[i].per_amplitude == b.transitions[i].per_amplitude);
  }
  CHECK(a.reach == b.reach);
  CHECK(a.reach_squared == b.reach_squared);
  REQUIRE(a.modal == b.modal);
  if (!a.modal) return;
  CHECK(a.V == b.V);
  CHECK(a.V_inverse == b.V_inverse);
  CHECK(a.lambda == b.lambda);
  CHECK(a.phi == b.phi);
  CHECK(a.g_plus == b.g_plus);
  CHECK(a.g_minus == b.g_minus);
  CHECK(a.force_V == b.force_V);
  CHECK(a.gap_zero == b.gap_zero);
  CHECK(a.gap_plus == b.gap_plus);
  CHECK(a.gap_minus == b.gap_minus);
}

}  // namespace

TEST_CASE("a mode built from another frequency's kept structure equals one built from scratch, to the last bit") {
  const char* sources[] = {// a fluid column behind a slider-capped spring: a mass (a conjugate pair), the cap's node rigid or free
                           "model m { series f { slider cap (fy = 60 N)\n spring k1 (k = 600 N/mm)\n parallel y { inerter column (b = 40 kg)\n"
                           " dashpot channel (c = 3.0 N*s/mm)\n spring bulge (k = 150 N/mm) } } }",
                           // a dashpot and a slider before a Maxwell arm: damped massless nodes, the drive's rate on the dashpot
                           "model m { series arm { dashpot d (c = 0.5 N*s/mm)\n slider s (fy = 45 N)\n maxwell x (k = 300 N/mm, tau = 20 ms) } }",
                           // a gap and a slider before a spring: undamped massless nodes, condensed
                           "model m { series s { gap g (width = 0.2 mm)\n slider s (fy = 20 N)\n spring k (k = 300 N/mm) } }"};
  int built = 0;
  for (const char* source : sources) {
    const runtime::PwlBranch branch = branch_of(source);
    for (const runtime::PwlModeCode& code : every_code(branch)) {
      CAPTURE(std::string(source));
      CAPTURE(code.size());
      const double first = 2.0 * std::numbers::pi * 3.0, second = 2.0 * std::numbers::pi * 41.0;
      runtime::PwlModeStructure kept, fresh;
      runtime::PwlModeSystem at_first, reused, scratch;
      const bool determinate = runtime::build_pwl_mode(branch, code, first, at_first, &kept);
      CHECK(runtime::build_pwl_mode(branch, code, second, reused, &kept) == determinate);
      CHECK(runtime::build_pwl_mode(branch, code, second, scratch, &fresh) == determinate);
      if (!determinate) continue;
      ++built;
      check_same(reused, scratch);
      // And at the first frequency again: the build that kept the structure equals one from it.
      runtime::PwlModeSystem again;
      REQUIRE(runtime::build_pwl_mode(branch, code, first, again, &kept));
      check_same(again, at_first);
      CHECK(at_first.A != reused.A);  // the drive's columns differ between the frequencies
    }
  }
  CHECK(built >= 10);
}

}  // namespace pwl_mode_test
