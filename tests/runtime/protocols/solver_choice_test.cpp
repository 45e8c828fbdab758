// Which backend `solver = auto | fixed | sundials` picks.
#include "runtime/protocols/solver_choice.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

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
