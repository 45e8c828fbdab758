// Compilation: canonical forms, root groups, state layout, re-parameterisation.
#include "runtime/network.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

using namespace rheo;

TEST_CASE("root leaves are grouped by kind into flat arrays") {
  const auto net = test::network_from(R"(
    model d { parallel { yeoh r (D10 = 389.43, D20 = -2.1094, D30 = 0.0786) maxwell m1 (k = 61.476, tau = 4.335 ms)
              friction f1 (k = 1016.6, uy = 101.58 um) friction f2 (k = 301.04, uy = 42.256 um) } })", "d");
  const auto& t = net.topology();
  CHECK(t.yeohs.size() == 1);
  CHECK(t.maxwells.size() == 1);
  CHECK(t.frictions.size() == 2);
  CHECK(t.subtrees.empty());
  CHECK(t.state_size == 3);
  CHECK(t.internal_nodes == 0);
  CHECK_FALSE(t.has_rate_jump);
  // friction given uy stores fy = k uy
  CHECK(net.coefficients().friction_fy[0] == doctest::Approx(1016.6 * 0.10158));
  CHECK(net.coefficients().maxwell_c[0] == doctest::Approx(61.476 * 4.335e-3));
}

TEST_CASE("nested blocks: single-child blocks vanish, same-kind nesting is spliced") {
  const auto net = test::network_from("model n { parallel { parallel { spring a (k = 1) } series { series { spring b (k = 2) slider s (fy = 1) } dashpot d (c = 1) } } }", "n");
  const auto& t = net.topology();
  CHECK(t.springs.size() == 1);
  REQUIRE(t.subtrees.size() == 1);
  const auto& chain = t.nodes[static_cast<std::size_t>(t.subtrees[0])];
  CHECK(chain.kind == runtime::NodeKind::series);
  // spring b and dashpot d are fused into one exact Maxwell member; the slider stays.
  CHECK(chain.child_count == 2);
  CHECK(t.internal_nodes == 1);
}

TEST_CASE("a dashpot with no spring in series makes the force jump with the rate") {
  CHECK(test::network_from("model kv { spring s (k = 1) dashpot d (c = 1) }", "kv").topology().has_rate_jump);
  CHECK_FALSE(test::network_from("model m { maxwell m (k = 1, c = 1) }", "m").topology().has_rate_jump);
  CHECK(test::network_from("model b { series { slider s (fy = 1) dashpot d (c = 1) } }", "b").topology().has_rate_jump);
}

TEST_CASE("with_parameters re-evaluates derived parameters") {
  const auto net = test::network_from("model f { friction f (k = 100, uy = 0.1) }", "f");
  std::vector<double> values = net.parameters();
  const auto& params = net.model().parameters;
  for (std::size_t i = 0; i < params.size(); ++i)
    if (params[i].path == "f.k") values[i] = 300.0;
  const auto changed = net.with_parameters(values);
  CHECK(changed.coefficients().friction_k[0] == 300.0);
  CHECK(changed.coefficients().friction_fy[0] == doctest::Approx(30.0));
  CHECK(net.coefficients().friction_fy[0] == doctest::Approx(10.0));  // the original is untouched
}
