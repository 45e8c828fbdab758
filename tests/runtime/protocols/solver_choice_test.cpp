// Which backend `solver = auto | fixed | sundials` picks.
#include "runtime/protocols/solver_choice.hpp"
#include "dae/two_tone_reference.hpp"
#include "runtime/protocols/run_history.hpp"
#include "support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

namespace solver_choice_test {

using namespace rheo;

TEST_CASE("auto takes SUNDIALS for a network with an inerter, fixed steps otherwise") {
  const auto plain = test::network_from("model m { spring k (k = 1 N/mm)\n maxwell x (k = 1 N/mm, tau = 1 s) }", "m");
  const auto inertial = test::network_from("model m { spring k (k = 1 N/mm)\n series s { spring k1 (k = 1 N/mm)\n inerter b (b = 1 kg) } }", "m");
  CHECK_FALSE(runtime::uses_sundials(plain, runtime::SolverChoice::automatic));
  CHECK(runtime::uses_sundials(inertial, runtime::SolverChoice::automatic));
  CHECK(runtime::uses_sundials(plain, runtime::SolverChoice::sundials));
  CHECK_FALSE(runtime::uses_sundials(inertial, runtime::SolverChoice::fixed));
}

TEST_CASE("auto takes SUNDIALS when series and parallel blocks alternate more than 3 deep") {
  // Blocks below the model's body: series { spring; parallel { spring; series { ... } } }.
  auto alternating = [](int depth) {
    std::string open, close;
    for (int i = 0; i < depth; ++i) {
      open += (i % 2 == 0 ? "series { spring s" : "parallel { spring p") + std::to_string(i) + " (k = 1 N/mm) ";
      close += " }";
    }
    return test::network_from("model m { " + open + "dashpot d (c = 1 N*s/mm)" + close + " }", "m");
  };
  CHECK_FALSE(runtime::uses_sundials(alternating(2), runtime::SolverChoice::automatic));
  CHECK_FALSE(runtime::uses_sundials(alternating(3), runtime::SolverChoice::automatic));
  CHECK(runtime::uses_sundials(alternating(4), runtime::SolverChoice::automatic));
  CHECK(runtime::uses_sundials(alternating(40), runtime::SolverChoice::automatic));
  CHECK_FALSE(runtime::uses_sundials(alternating(40), runtime::SolverChoice::fixed));
}

TEST_CASE("auto takes fixed steps for a network with a bouc_wen inside a series block, whatever its inerters and depth") {
  const auto nested = [](const char* where) {
    return test::network_from(fmt::format("model m {{ series {{ spring (k = 100 N/mm)\n {}\n"
                                          " series {{ spring (k = 10 N/mm) parallel {{ inerter (b = 0.01 kg) dashpot (c = 1 N*s/mm) }} }} }} }}",
                                          where),
                              "m");
  };
  const auto bouc_wen = "bouc_wen (k = 50 N/mm, n = 3, fy = 0.5 N)";
  CHECK_FALSE(runtime::uses_sundials(nested(bouc_wen), runtime::SolverChoice::automatic));
  CHECK_FALSE(
      runtime::uses_sundials(nested(fmt::format("parallel {{ spring (k = 1 N/mm) {} }}", bouc_wen).c_str()), runtime::SolverChoice::automatic));
  CHECK(runtime::uses_sundials(nested(bouc_wen), runtime::SolverChoice::sundials));
  // Between terminal and ground (in the body, or in parallel blocks only) it is no reason.
  const auto beside = test::network_from(
      fmt::format("model m {{ {}\n parallel {{ {} }}\n series {{ spring (k = 10 N/mm) inerter (b = 0.01 kg) }} }}", bouc_wen, bouc_wen), "m");
  CHECK(runtime::uses_sundials(beside, runtime::SolverChoice::automatic));
}

// Differential seed 37, model 85: sharp bouc_wen elements (n up to 3.8, yielding at 13 um) in series
// blocks beside inerters, five blocks deep. Auto took IDA (the inerters, the depth), whose
// corrector failed at every step size 0.1 us after the drive sample at 5 ms, where the elongation
// rates of the bouc_wen elements reverse behind one at z = 0.999998 (IDA_CONV_FAIL: a default
// `rheo simulate` exited 5; IDA runs it now, dae_bouc_wen_test). Auto takes fixed steps, far
// faster there; on the differential test's two-tone drive
// at one step a sample (the inerters' w dt up to 1.8) they lie within the differential test's
// history tolerance, 2e-2 of max |F|, of fixed steps at 64 and 128 a sample, extrapolated
// (observed 1.3e-2).
TEST_CASE("auto runs sharp bouc_wen elements in series blocks beside inerters (differential seed 37, model 85)") {
  const auto network = test::network_from(test::kSeed37Model85, "m");
  CHECK_FALSE(runtime::uses_sundials(network, runtime::SolverChoice::automatic));
  const auto history = runtime::run_history(network, test::two_tone_drive(1), false);
  const double gap = test::gap_to_extrapolated_fixed_steps(network, history.force);
  MESSAGE("auto against fine fixed steps: ", gap, " of max |F|");
  CHECK(gap < 2e-2);
}

}  // namespace solver_choice_test
