// Coordinates of the variable-step backend per switching mode: independent rates, inerters
// first, driven rates, and the inerter that a stuck slider would tie to the drive.
#include "runtime/dae/dae_modes.hpp"
#include "runtime/core/errors.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

namespace dae_modes_test {

using namespace rheo;

TEST_CASE("two dashpots in parallel share one coordinate") {
  const auto graph = runtime::DaeGraph::build(test::network_from(
      "model m { series s { spring k (k = 1 N/mm)\n parallel p { dashpot a (c = 1 N*s/mm)\n dashpot b (c = 2 N*s/mm) } } }", "m"));
  const auto k = runtime::ModeKinematics::make(graph, {});
  REQUIRE(k.coordinates == 1);
  CHECK(k.alpha[0] == doctest::Approx(1.0));
  CHECK(k.alpha[1] == doctest::Approx(1.0));
  CHECK(k.beta[0] == 0.0);
}

TEST_CASE("an inerter is chosen before a dashpot on the same node and gets a velocity slot") {
  const auto graph = runtime::DaeGraph::build(
      test::network_from("model m { series s { spring k (k = 1 N/mm)\n parallel p { dashpot d (c = 1 N*s/mm)\n inerter b (b = 1 kg) } } }", "m"));
  const auto k = runtime::ModeKinematics::make(graph, {});
  REQUIRE(k.coordinates == 1);
  CHECK(k.coordinate_rate[0] == 1);  // the inerter, second rate edge
  CHECK(k.velocity_slot[0] == 0);
}

TEST_CASE("a stuck slider drives the dashpot behind it: e' = u'") {
  const auto graph = runtime::DaeGraph::build(
      test::network_from("model m { spring k0 (k = 1 N/mm)\n series s { slider f (fy = 1 N)\n dashpot d (c = 1 N*s/mm) } }", "m"));
  const auto stuck = runtime::ModeKinematics::make(graph, {0});
  CHECK(stuck.coordinates == 0);
  CHECK(stuck.beta[0] == doctest::Approx(1.0));
  const auto slipping = runtime::ModeKinematics::make(graph, {1});
  CHECK(slipping.coordinates == 1);
  CHECK(slipping.beta[0] == 0.0);
}

TEST_CASE("an inerter held to the drive by a stuck slider is refused with advice") {
  // Network::compile refuses this topology already; the graph is built by hand to check the
  // backend's own guard.
  runtime::DaeGraph graph;
  graph.model = "m";
  graph.internal_nodes = 1;
  graph.edges = {{runtime::EdgeKind::spring, runtime::kTerminal, runtime::kGround, {1.0}, "k0", {}},
                 {runtime::EdgeKind::slider, runtime::kTerminal, 0, {1.0}, "s.f", {}},
                 {runtime::EdgeKind::inerter, 0, runtime::kGround, {1.0}, "s.b", {}}};
  graph.rate_edges = {2};
  graph.switch_edges = {1};
  CHECK_THROWS_WITH_AS(runtime::ModeKinematics::make(graph, {0}), doctest::Contains("inerter 's.b' of model 'm' is held rigidly to the drive"),
                       runtime::NumericalError);
  CHECK_NOTHROW(runtime::ModeKinematics::make(graph, {1}));
}

}  // namespace dae_modes_test
