// Which subtrees the event-driven periodic state takes (pwl_branch.hpp), and their graphs.
#include "runtime/closed_form/periodic_closed_form.hpp"
#include "runtime/closed_form/pwl_branch.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

#include <string>

namespace pwl_branch_test {

using namespace rheo;

TEST_CASE("a friction element behind a spring: three nodes' worth of edges, one switch") {
  const auto net = test::network_from(
      "model n { spring k0 (k = 1 N/mm)\n series c { spring k1 (k = 300 N/mm)\n friction f (k = 600 N/mm, uy = 0.1 mm) } }", "n");
  runtime::PwlBranch branch;
  REQUIRE(runtime::PwlBranch::build(net, net.topology().subtrees[0], branch));
  CHECK(branch.internal_nodes == 2);  // the chain's junction and the friction element's own node
  REQUIRE(branch.edges.size() == 3);
  REQUIRE(branch.switches.size() == 1);
  const runtime::PwlEdge& slider = branch.edges[static_cast<std::size_t>(branch.switches[0])];
  CHECK(slider.kind == runtime::PwlEdgeKind::slider);
  CHECK(slider.value == doctest::Approx(60.0));  // fy = k uy [N]
  CHECK(slider.b == runtime::kPwlGround);
}

TEST_CASE("branches the event path does not take") {
  runtime::PwlBranch branch;
  const auto bouc = test::network_from("model b { series c { spring k (k = 1 N/mm)\n bouc_wen w (k = 1 N/mm, fy = 1 N, n = 2) } }", "b");
  CHECK_FALSE(runtime::PwlBranch::build(bouc, bouc.topology().subtrees[0], branch));
  CHECK_FALSE(runtime::has_closed_form_periodic_state(bouc));
  // Two sliders side by side close a loop of rigid edges: their forces would be indeterminate.
  const auto loop = test::network_from("model l { series c { spring k (k = 1 N/mm)\n parallel p { slider a (fy = 1 N)\n slider b (fy = 2 N) } } }",
                                       "l");
  CHECK_FALSE(runtime::PwlBranch::build(loop, loop.topology().subtrees[0], branch));
  // A chain of twelve Maxwell arms behind a slider: 24 internal nodes, more state than the event
  // path's fixed-size storage holds (kPwlMaxDim); it time-steps.
  std::string chain = "model big { series c { slider s (fy = 1 N)\n";
  for (int i = 0; i < 12; ++i) chain += "maxwell m" + std::to_string(i) + " (k = 10 N/mm, tau = 1 ms)\n";
  chain += "} }";
  const auto big = test::network_from(chain, "big");
  CHECK_FALSE(runtime::PwlBranch::build(big, big.topology().subtrees[0], branch));
  CHECK_FALSE(runtime::has_closed_form_periodic_state(big));
}

}  // namespace pwl_branch_test
