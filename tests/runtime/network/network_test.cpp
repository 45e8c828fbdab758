// Compilation: canonical forms, root groups, state layout, re-parameterisation.
#include "runtime/network/network.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/closed_form/periodic_closed_form.hpp"
#include "runtime/network/leaf_kernels.hpp"
#include "runtime/network/springpot.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <vector>

namespace network_test {

using namespace rheo;

TEST_CASE("root leaves are grouped by kind into flat arrays") {
  const auto net = test::network_from(R"(
    model d { parallel { yeoh r (D10 = 389.43, D20 = -2.1094, D30 = 0.0786) maxwell m1 (k = 61.476, tau = 4.335 ms)
              friction f1 (k = 1016.6, uy = 101.58 um) friction f2 (k = 301.04, uy = 42.256 um) } })",
                                      "d");
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
  CHECK(net.coefficients().maxwell_c[0] == doctest::Approx(61.476 * 4.335e-3).scale(0.0));
}

TEST_CASE("nested blocks: single-child blocks vanish, same-kind nesting is spliced") {
  const auto net = test::network_from(
      "model n { parallel { parallel { spring a (k = 1) } series { series { spring b (k = 2) slider s (fy = 1) } dashpot d (c = 1) } } }", "n");
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

TEST_CASE("inerter, quadratic_dashpot, gap and bouc_wen leaves are subtrees, also in the root block") {
  const auto net = test::network_from(R"(
    model n { spring k (k = 10) inerter m (b = 1 kg) quadratic_dashpot q (cq = 1 N*s^2/mm^2)
              bouc_wen w (k = 10, n = 2, fy = 1) series { gap g (width = 0.1 mm) spring s (k = 5) } })",
                                      "n");
  const auto& t = net.topology();
  CHECK(t.springs.size() == 1);
  REQUIRE(t.subtrees.size() == 4);
  const auto& inerter = t.nodes[static_cast<std::size_t>(t.subtrees[0])];
  CHECK(inerter.kind == runtime::NodeKind::inerter);
  CHECK(inerter.drive_prescribed);
  CHECK(inerter.slots == 6);  // e, F, two rates, two step lengths
  // 6 + 2 (quadratic_dashpot) + 2 (bouc_wen) + 3 x 2 (chain, gap, spring)
  CHECK(t.state_size == 16);
  REQUIRE(t.state_scales.size() == 16u);
  using S = runtime::StateScale;
  CHECK(t.state_scales[0] == S::length);
  CHECK(t.state_scales[1] == S::force);
  CHECK(t.state_scales[2] == S::velocity);
  CHECK(t.state_scales[4] == S::time);
  CHECK(t.state_scales[15] == S::force);
  CHECK_FALSE(runtime::has_closed_form_periodic_state(net));
  CHECK(t.has_rate_jump);  // the quadratic dashpot
  CHECK_FALSE(t.is_linear);
  // An inerter behind a spring integrates the force (Newmark): velocity as third slot.
  const auto chain = test::network_from("model c { series { spring s (k = 1) inerter m (b = 1 kg) } }", "c");
  const auto& nodes = chain.topology().nodes;
  CHECK(nodes[2].kind == runtime::NodeKind::inerter);
  CHECK_FALSE(nodes[2].drive_prescribed);
  CHECK(nodes[2].slots == 3);
  CHECK(chain.topology().is_linear);
}

TEST_CASE("rate jumps pass through members rigid to a rate jump: sliders, gaps, inerters") {
  auto jumps = [](const char* source) { return test::network_from(source, "j").topology().has_rate_jump; };
  CHECK(jumps("model j { quadratic_dashpot q (cq = 1 N*s^2/mm^2) }"));
  CHECK(jumps("model j { series { inerter m (b = 1 kg) dashpot d (c = 1) } }"));
  CHECK(jumps("model j { series { gap g (width = 1 mm) dashpot d (c = 1) } }"));
  CHECK_FALSE(jumps("model j { spring k (k = 1) inerter m (b = 1 kg) }"));
  CHECK_FALSE(jumps("model j { series { spring k (k = 1) quadratic_dashpot q (cq = 1 N*s^2/mm^2) } }"));
  CHECK_FALSE(jumps("model j { bouc_wen w (k = 1, n = 1, fy = 1) }"));
}

TEST_CASE("placement: gaps only in series with a compliant member, inerters never rigidly driven") {
  auto error_of = [](const char* source) -> std::string {
    try {
      test::network_from(source, "p");
    } catch (const runtime::ModelError& e) {
      return e.what();
    }
    return "";
  };
  const std::string root = error_of("model p { spring s (k = 1) gap play (width = 0.2 mm) }");
  CHECK(root.find("gap 'play' is in the model's parallel block") != std::string::npos);
  CHECK(root.find("series { gap play (width = 0.2 mm)  spring (k = 500 N/mm) }") != std::string::npos);
  // The placement each message proposes is a statement that builds (#22 item 1).
  auto proposal = [](const std::string& message) {
    const auto begin = message.find("series {"), end = message.find(" }", begin);
    REQUIRE(begin != std::string::npos);
    REQUIRE(end != std::string::npos);
    return message.substr(begin, end + 2 - begin);
  };
  CHECK_NOTHROW(test::network_from("model p { spring s (k = 1) " + proposal(root) + " }", "p"));
  CHECK(error_of("model p { series { spring s (k = 1) parallel { gap g (width = 1 mm) spring t (k = 1) } } }")
            .find("gap 'g' is inside a parallel block") != std::string::npos);
  CHECK(error_of("model p { series { gap g (width = 1 mm) slider f (fy = 1) } }").find("no compliant member") != std::string::npos);
  CHECK(error_of("model p { series { gap g (width = 1 mm) parallel { inerter m (b = 1 kg) spring s (k = 1) } } }").find("no compliant member") !=
        std::string::npos);
  const std::string inerter = error_of("model p { series { slider f (fy = 1) inerter m (b = 1 kg) } }");
  CHECK(inerter.find("inerter 'm' is connected to the drive through sliders, gaps or inerters only") != std::string::npos);
  CHECK_NOTHROW(test::network_from("model p { " + proposal(inerter) + " }", "p"));
  const std::string nested = error_of("model p { series outer { spring s (k = 1) parallel { gap g (width = 1 mm) spring t (k = 1) } } }");
  CHECK(nested.find("gap g (width = 1 mm)") != std::string::npos);  // the name as written, not its path
  CHECK(error_of("model p { series { inerter a (b = 1 kg) inerter b (b = 2 kg) } }").find("inerter 'a'") != std::string::npos);
  // Accepted: compliant members in series, also further out than the inerter's own block.
  CHECK(error_of("model p { series { gap g (width = 1 mm) maxwell m (k = 1, tau = 1 ms) } }").empty());
  CHECK(error_of("model p { series { gap g (width = 1 mm) slider f (fy = 1) spring s (k = 1) } }").empty());
  CHECK(error_of("model p { series { spring s (k = 1) parallel { series { slider f (fy = 1) inerter m (b = 1 kg) } dashpot d (c = 1) } } }").empty());
  CHECK(error_of("model p { inerter m (b = 1 kg) }").empty());
}

TEST_CASE("a springpot is a Maxwell chain: spliced into the root group, kept whole when nested, rederived on new parameters") {
  const auto root = test::network_from(R"(
    model r { spring e (k = 10) parallel { springpot sp (k = 50, alpha = 0.3, tau = 10 ms) maxwell m (k = 5, tau = 1 ms) } })",
                                       "r");
  const auto& t = root.topology();
  const int modes = runtime::springpot_mode_count(0.01, 1000.0);
  REQUIRE(t.springpots.size() == 1);
  CHECK(t.springpots[0].modes == modes);
  CHECK(t.derived_parameters == 2 * modes);
  CHECK(t.maxwells.size() == static_cast<std::size_t>(modes) + 1);
  CHECK(t.subtrees.empty());
  CHECK(runtime::has_closed_form_periodic_state(root));
  const auto& probe = t.probes[1];
  CHECK(probe.path == "sp");
  CHECK(probe.source == runtime::ElementProbe::Source::root_springpot);
  CHECK(probe.count == modes);
  // The derived modes are the chain of runtime/network/springpot.hpp for the element's parameters.
  std::vector<double> k(static_cast<std::size_t>(modes)), c(k.size());
  runtime::springpot_modes({50.0, 0.3, 0.01, 0.01, 1000.0}, k, c);
  CHECK(root.coefficients().maxwell_k[static_cast<std::size_t>(probe.index)] == k[0]);
  CHECK(root.coefficients().maxwell_c[static_cast<std::size_t>(probe.index + modes - 1)] == c.back());

  // New alpha: the same number of modes with new values.
  std::vector<double> values = root.parameters();
  values[2] = 0.6;  // e.k, sp.k, sp.alpha, ...
  REQUIRE(root.model().parameters[2].path == "sp.alpha");
  const auto refit = root.with_parameters(values);
  runtime::springpot_modes({50.0, 0.6, 0.01, 0.01, 1000.0}, k, c);
  CHECK(refit.coefficients().maxwell_k[static_cast<std::size_t>(probe.index)] == k[0]);
  CHECK(refit.parameters().size() == root.parameters().size());

  const auto nested = test::network_from(
      "model n { series { spring e (k = 100) springpot sp (k = 50, alpha = 0.5, tau = 1 ms, f_low = 1 Hz, f_high = 100 Hz) } }", "n");
  const auto& tn = nested.topology();
  REQUIRE(tn.subtrees.size() == 1);
  CHECK(tn.maxwells.empty());
  const auto& sp = tn.probes[1];
  CHECK(sp.source == runtime::ElementProbe::Source::tree_node);
  CHECK(tn.nodes[static_cast<std::size_t>(sp.index)].child_count == runtime::springpot_mode_count(1.0, 100.0));
}

TEST_CASE("a lone springpot is the root group's one chain (its modes are no branches of their own)") {
  const auto lone = test::network_from("model l { springpot sp (k = 50, alpha = 0.3, tau = 10 ms) }", "l");
  const auto& t = lone.topology();
  REQUIRE(t.probes.size() == 1);
  CHECK(t.probes[0].source == runtime::ElementProbe::Source::root_springpot);
  CHECK(t.probes[0].index == 0);
  CHECK(t.probes[0].count == runtime::springpot_mode_count(0.01, 1000.0));
  CHECK(t.maxwells.size() == static_cast<std::size_t>(t.probes[0].count));
}

TEST_CASE("a springpot band with f_low not below f_high is a model error at the element") {
  CHECK_THROWS_WITH_AS(test::network_from("model b {\n  springpot sp (k = 5, alpha = 0.5, tau = 1 ms, f_low = 10 Hz, f_high = 1 Hz)\n}", "b"),
                       doctest::Contains("test.rheo:2:3: error: model 'b': springpot 'sp' has f_low = 10 Hz not below f_high = 1 Hz"),
                       runtime::ModelError);
}

TEST_CASE("one-sided friction elements and sliders, and poly springs, are subtrees, symmetric ones stay in the root groups") {
  const auto net = test::network_from(R"(
    model a { friction f (k = 2 N/mm, fy = 3 N)  friction g (k = 2 N/mm, fy_pos = 3 N, fy_neg = 5 N)
              slider s (fy = 1 N)  slider t (fy_pos = 1 N, fy_neg = 2 N)  poly_spring p (k1 = 10 N/mm, k2 = 1 N/mm^2) })",
                                      "a");
  const auto& t = net.topology();
  CHECK(t.frictions.size() == 1);
  CHECK(t.sliders.size() == 1);
  REQUIRE(t.subtrees.size() == 3);
  const auto& g = t.nodes[static_cast<std::size_t>(t.subtrees[0])];
  CHECK(g.kind == runtime::NodeKind::friction);
  CHECK(net.parameter(g.param[1]) == 3.0);  // fy_pos
  CHECK(net.parameter(g.param[2]) == 5.0);  // fy_neg
  const auto& s = t.nodes[static_cast<std::size_t>(t.subtrees[1])];
  CHECK(net.parameter(s.param[0]) == 1.0);
  CHECK(net.parameter(s.param[1]) == 2.0);
  CHECK(t.nodes[static_cast<std::size_t>(t.subtrees[2])].kind == runtime::NodeKind::poly_spring);
  // A symmetric friction element nested in a chain reads fy from both cap slots.
  const auto nested = test::network_from("model n { series c { spring a (k = 1)  friction f (k = 2 N/mm, fy = 3 N) } }", "n");
  const auto& f = nested.topology().nodes[static_cast<std::size_t>(nested.topology().subtrees[0]) + 2];
  REQUIRE(f.kind == runtime::NodeKind::friction);
  CHECK(f.param[2] == f.param[1]);
}

TEST_CASE("a gap whose rest position lies outside its play is a model error at its center, a fit's values beyond act as the stop") {
  CHECK_THROWS_WITH_AS(test::network_from("model b {\n  series c { gap g (width = 1 mm, center = 0.6 mm)  spring k (k = 1) }\n}", "b"),
                       doctest::Contains("error: model 'b': gap 'c.g' has center = 0.6 mm, beyond half its width (0.5 mm)"), runtime::ModelError);
  CHECK_NOTHROW(test::network_from("model b { series c { gap g (width = 1 mm, center = -0.5 mm)  spring k (k = 1) } }", "b"));
  const auto net = test::network_from("model b { series c { gap g (width = 1 mm, center = 0.2 mm)  spring k (k = 1) } }", "b");
  std::vector<double> values = net.parameters();
  values[static_cast<std::size_t>(test::parameter_index(net, "c.g.center"))] = 3.0;
  CHECK_NOTHROW(static_cast<void>(net.with_parameters(values)));
  CHECK(runtime::gap_center(1.0, 3.0) == 0.5);
  CHECK(runtime::gap_center(1.0, -0.2) == -0.2);
}

}  // namespace network_test
