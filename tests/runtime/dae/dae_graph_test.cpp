// The edge graph of the variable-step backend: expansion of composite leaves, node numbering,
// and the networks it refuses with advice.
#include "runtime/dae/dae_graph.hpp"
#include "runtime/core/errors.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

namespace dae_graph_test {

using namespace rheo;
using runtime::EdgeKind;

TEST_CASE("maxwell and friction expand into spring + dashpot / slider through a new node") {
  const auto graph = runtime::DaeGraph::build(test::network_from(
      "model m { maxwell m1 (k = 10 N/mm, tau = 0.1 s)\n friction f (k = 5 N/mm, fy = 2 N)\n series s { spring a (k = 1 N/mm)\n dashpot d (c = 1 N*s/mm) } }",
      "m"));
  REQUIRE(graph.edges.size() == 6);
  CHECK(graph.internal_nodes == 3);
  CHECK(graph.edges[0].kind == EdgeKind::spring);
  CHECK(graph.edges[0].a == runtime::kTerminal);
  CHECK(graph.edges[1].kind == EdgeKind::dashpot);
  CHECK(graph.edges[1].p[0] == doctest::Approx(1.0));  // c = k tau
  CHECK(graph.edges[1].b == runtime::kGround);
  CHECK(graph.edges[0].b == graph.edges[1].a);
  CHECK(graph.edges[3].kind == EdgeKind::slider);
  CHECK(graph.rate_edges == std::vector<int>{1, 5});
  CHECK(graph.switch_edges == std::vector<int>{3});
  REQUIRE(graph.probes.size() == 4);
  CHECK(graph.probes[0].edges == std::vector<int>{0, 1});
  CHECK(graph.probes[3].path == "s.d");
}

TEST_CASE("a gap stores its half width") {
  const auto graph = runtime::DaeGraph::build(test::network_from("model m { series s { gap g (width = 0.4 mm)\n spring k (k = 3 N/mm) } }", "m"));
  CHECK(graph.edges[0].kind == EdgeKind::gap);
  CHECK(graph.edges[0].p[0] == doctest::Approx(0.2).scale(0.0));
}

TEST_CASE("refused: an inerter between terminal and ground, and sliders meeting at a free node") {
  CHECK_THROWS_WITH_AS(runtime::DaeGraph::build(test::network_from("model m { inerter b (b = 1 kg)\n spring k (k = 1 N/mm) }", "m")),
                       doctest::Contains("inerter 'b' of model 'm' sits directly between the terminal and ground"), runtime::ModelError);
  CHECK_THROWS_WITH_AS(
      runtime::DaeGraph::build(test::network_from("model m { spring k (k = 1 N/mm)\n series s { slider a (fy = 1 N)\n slider b (fy = 2 N) } }", "m")),
      doctest::Contains("merge the sliders or put a spring between them"), runtime::ModelError);
}

TEST_CASE("refused: sliders in parallel, with the one slider they act as") {
  // While both stick their shares of the force are undetermined (IDACalcIC: IDA_NO_RECOVERY).
  const std::string symmetric =
      "model m { series c { spring k (k = 100 N/mm)\n parallel p { spring s (k = 10 N/mm)\n slider a (fy = 10 N)\n "
      "slider b (fy = 20 N) } } }";
  CHECK_THROWS_WITH_AS(runtime::DaeGraph::build(test::network_from(symmetric, "m")),
                       doctest::Contains("slider 'c.p.b' of model 'm' sits in parallel with slider 'c.p.a'"), runtime::ModelError);
  CHECK_THROWS_WITH_AS(runtime::DaeGraph::build(test::network_from(symmetric, "m")), doctest::Contains("merge the sliders into one (fy = 30 N)"),
                       runtime::ModelError);
  const std::string asymmetric =
      "model m { series c { spring k (k = 100 N/mm)\n parallel p { slider a (fy_pos = 10 N, fy_neg = 4 N)\n "
      "slider b (fy = 20 N) } } }";
  CHECK_THROWS_WITH_AS(runtime::DaeGraph::build(test::network_from(asymmetric, "m")),
                       doctest::Contains("merge the sliders into one (fy_pos = 30 N, fy_neg = 24 N)"), runtime::ModelError);
  // Friction elements in parallel are sliders behind springs of their own: accepted.
  CHECK_NOTHROW(runtime::DaeGraph::build(test::network_from(
      "model m { series c { spring k (k = 100 N/mm)\n parallel p { friction a (k = 5 N/mm, fy = 10 N)\n friction b (k = 7 N/mm, fy = 20 N) } } }",
      "m")));
}

TEST_CASE("refused: a slider between terminal and ground (issue 26 reproducer 01)") {
  CHECK_THROWS_WITH_AS(runtime::DaeGraph::build(test::network_from("model m { spring k (k = 100 N/mm)\n slider s (fy = 5 N) }", "m")),
                       doctest::Contains("slider 's' of model 'm' sits directly between the terminal and ground"), runtime::ModelError);
  // The same slider behind a spring (a friction element) has an internal node to hold.
  CHECK_NOTHROW(runtime::DaeGraph::build(test::network_from("model m { spring k (k = 100 N/mm)\n friction f (k = 10 N/mm, fy = 5 N) }", "m")));
}

TEST_CASE("refused: a nested bouc_wen in a network with sliders or gaps, not a bouc_wen driven directly") {
  const std::string series_slider = "model m { series c { bouc_wen b (k = 785 N/mm, n = 2, uy = 17 um)\n slider s (fy = 6.7 N) } }";
  CHECK_THROWS_WITH_AS(runtime::DaeGraph::build(test::network_from(series_slider, "m")),
                       doctest::Contains("bouc_wen 'c.b' of model 'm' sits inside a block of a network with sliders, gaps or friction"),
                       runtime::ModelError);
  const std::string elsewhere =
      "model m { friction f (k = 10 N/mm, fy = 1 N)\n series c { bouc_wen b (k = 100 N/mm, n = 2, fy = 1 N)\n spring k (k = 50 N/mm) } }";
  CHECK_THROWS_WITH_AS(runtime::DaeGraph::build(test::network_from(elsewhere, "m")), doctest::Contains("use solver = fixed"), runtime::ModelError);
  CHECK_NOTHROW(runtime::DaeGraph::build(
      test::network_from("model m { bouc_wen b (k = 100 N/mm, n = 2, fy = 1 N)\n friction f (k = 10 N/mm, fy = 1 N) }", "m")));
  CHECK_NOTHROW(runtime::DaeGraph::build(
      test::network_from("model m { series c { bouc_wen b (k = 100 N/mm, n = 2, fy = 1 N)\n spring k (k = 50 N/mm) } }", "m")));
}

}  // namespace dae_graph_test
