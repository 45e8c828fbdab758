// The Prony series of a model against two other paths to its complex stiffness: the harmonic
// protocol (`rheo simulate`'s path: the closed form for these networks) and the phasor
// composition of the checked element tree; and the refusals, leave-outs and geometry.
#include "runtime/export/prony_cards.hpp"

#include "runtime/closed_form/phasor.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <complex>
#include <numbers>
#include <string>

namespace prony_cards_test {

using namespace rheo;
namespace fe = runtime::fe;

namespace {

// K*(w) of the cards, in their units: M_inf + sum M_0 r_i i w tau_i / (1 + i w tau_i).
std::complex<double> cards_stiffness(const fe::PronyCards& c, double frequency) {
  const double w = 2.0 * std::numbers::pi * frequency;
  std::complex<double> k = c.long_term;
  for (const auto& t : c.terms)
    k += c.instantaneous * t.ratio * std::complex<double>(0.0, w * t.relaxation_time) / std::complex<double>(1.0, w * t.relaxation_time);
  return k;
}

std::complex<double> simulated(const runtime::Network& network, double frequency) {
  const auto p = runtime::simulate_harmonic_point(network, 0.5, frequency, runtime::HarmonicOptions{});
  return {p.measures.storage, p.measures.loss};
}

const char* kLinear = R"(model lin {
  spring eq (k = 120 N/mm)
  spring eq2 (k = 30 N/mm)
  maxwell m1 (k = 400 N/mm, tau = 2 ms)
  maxwell m2 (k = 80 N/mm, c = 40 N*s/mm)
  series arm {
    dashpot d (c = 3 N*s/mm)
    spring s (k = 60 N/mm)
  }
  parallel inner { maxwell m3 (k = 25 N/mm, tau = 3 s) }
})";

}  // namespace

TEST_CASE("prony cards: springs, maxwell elements and a spring-dashpot chain are the model's complex stiffness") {
  const auto network = test::network_from(kLinear, "lin");
  const fe::PronyCards c = fe::prony_cards(network, std::nullopt, {});
  CHECK(c.long_term == doctest::Approx(150.0).epsilon(1e-15));
  CHECK(c.instantaneous == doctest::Approx(150.0 + 400 + 80 + 60 + 25).epsilon(1e-15));
  REQUIRE(c.terms.size() == 4);
  CHECK(c.terms[0].element == "m1");
  CHECK(c.terms[1].relaxation_time == doctest::Approx(0.5).epsilon(1e-15).scale(0.0));  // c/k = 40/80
  CHECK(c.terms[2].element == "arm.s");
  CHECK(c.terms[2].ratio * c.instantaneous == doctest::Approx(60.0).epsilon(1e-14));
  CHECK(c.terms[2].relaxation_time == doctest::Approx(0.05).epsilon(1e-15).scale(0.0));
  CHECK(c.terms[3].element == "inner.m3");
  CHECK(c.springs == std::vector<std::string>{"eq", "eq2"});
  std::vector<double> values;
  for (const auto& p : network.model().parameters) values.push_back(p.value);
  for (double f : {1e-4, 0.01, 0.3, 3.0, 80.0, 1e4}) {
    const auto k = cards_stiffness(c, f);
    const auto phasor = *runtime::complex_stiffness(network.model(), values, f);
    CHECK(std::abs(k - phasor) <= 1e-13 * std::abs(phasor));
    const auto sim = simulated(network, f);
    CHECK(std::abs(k.real() / sim.real() - 1.0) <= 1e-12);
    CHECK(std::abs(k.imag() / sim.imag() - 1.0) <= 1e-12);
  }
}

TEST_CASE("prony cards: a springpot is its Maxwell chain, as rheo simulates it") {
  const auto network = test::network_from(R"(model gel {
  spring eq (k = 20 N/mm)
  springpot sp (k = 50 N/mm, alpha = 0.3, tau = 0.1 s, f_low = 0.01 Hz, f_high = 1000 Hz)
})",
                                          "gel");
  const fe::PronyCards c = fe::prony_cards(network, std::nullopt, {});
  REQUIRE(c.springpots.size() == 1);
  CHECK(c.terms.size() == static_cast<std::size_t>(c.springpots[0].modes));
  CHECK(c.springpots[0].f_low == 0.01);
  for (double f : {0.001, 0.02, 1.0, 50.0, 900.0, 1e5}) {
    const auto k = cards_stiffness(c, f);
    const auto sim = simulated(network, f);
    CHECK(std::abs(k.real() / sim.real() - 1.0) <= 1e-12);
    CHECK(std::abs(k.imag() / sim.imag() - 1.0) <= 1e-12);
  }
  // Inside its band the chain is the springpot: K* = 20 + 50 (i w 0.1)^0.3 within 5e-4.
  std::vector<double> values;
  for (const auto& p : network.model().parameters) values.push_back(p.value);
  for (double f : {0.05, 1.0, 200.0}) {
    const auto exact = *runtime::complex_stiffness(network.model(), values, f);
    CHECK(std::abs(cards_stiffness(c, f) - exact) <= 5e-4 * std::abs(exact));
  }
}

TEST_CASE("prony cards: a geometry turns stiffness into modulus, M = K h / A, and keeps the ratios") {
  const auto network = test::network_from(kLinear, "lin");
  const fe::PronyCards k = fe::prony_cards(network, std::nullopt, {});
  const fe::PronyCards m = fe::prony_cards(network, fe::Geometry{40.0, 20.0, "test"}, {});
  CHECK(m.instantaneous == doctest::Approx(k.instantaneous * 0.5).epsilon(1e-15));
  CHECK(m.long_term == doctest::Approx(150.0 * 0.5).epsilon(1e-15));
  REQUIRE(m.terms.size() == k.terms.size());
  for (std::size_t i = 0; i < m.terms.size(); ++i) CHECK(m.terms[i].ratio == k.terms[i].ratio);
  CHECK(m.geometry->source == "test");
}

TEST_CASE("prony cards: every element without a Prony counterpart is refused at its line and column") {
  const std::string source =
      "model m {\n"             // 1
      "  spring k (k = 100)\n"  // 2
      "  friction f1 (k = 50, fy = 2)\n"
      "  yeoh rubber (D10 = 10, D20 = 0, D30 = 0)\n"
      "  dashpot c (c = 1)\n"
      "  series chain { spring a (k = 1) spring b (k = 2) dashpot d (c = 1) }\n"
      "  series play { gap g (width = 0.2) spring e (k = 5) }\n"
      "  maxwell m1 (k = 10, tau = 1 ms)\n"
      "}";
  const auto network = test::network_from(source, "m");
  try {
    fe::prony_cards(network, std::nullopt, {});
    FAIL("a friction element was exported");
  } catch (const ModelError& e) {
    const std::string what = e.what();
    CHECK(what.find("test.rheo:3:3: error: model 'm': friction 'f1' is rate-independent friction") != std::string::npos);
    CHECK(what.find("--leave-out f1") != std::string::npos);
    CHECK(what.find("test.rheo:4:3: error: model 'm': yeoh 'rubber' is a non-linear spring") != std::string::npos);
    CHECK(what.find("test.rheo:5:3: error: model 'm': dashpot 'c' acts in parallel") != std::string::npos);
    CHECK(what.find("test.rheo:6:3: error: model 'm': series 'chain' is a linear block, but not one spring and one dashpot") != std::string::npos);
    CHECK(what.find("gap 'play.g' is free play") != std::string::npos);
    CHECK(what.find("--leave-out play ") != std::string::npos);
    CHECK(what.find("'m1'") == std::string::npos);  // the maxwell element is no refusal
  }
  // Left out by name, the same model exports, and says what it lacks.
  const fe::PronyCards c = fe::prony_cards(network, std::nullopt, {"f1", "rubber", "c", "chain", "play"});
  REQUIRE(c.left_out.size() == 5);
  CHECK(c.left_out[0].path == "f1");
  CHECK(c.left_out[0].where.line == 3);
  CHECK(c.left_out[3].kind == lang::ElementKind::series);
  CHECK(c.long_term == 100.0);
  CHECK(c.terms.size() == 1);
}

TEST_CASE("prony cards: --leave-out names a branch, with advice when it does not") {
  const auto network = test::network_from(
      "model m { spring k (k = 1)  series play { gap g (width = 0.2) spring e (k = 5) }  friction f (k = 1, fy = 1) }", "m");
  CHECK_THROWS_WITH_AS(
      fe::prony_cards(network, std::nullopt, {"play.g", "f"}),
      doctest::Contains(
          "--leave-out 'play.g': that element is part of series 'play', a branch of model 'm''s parallel block; leave out the whole branch: --leave-out play"),
      UsageError);
  CHECK_THROWS_WITH_AS(fe::prony_cards(network, std::nullopt, {"plya", "f"}),
                       doctest::Contains("has no element of that name; did you mean 'play'?"), UsageError);
  CHECK_THROWS_WITH_AS(fe::prony_cards(network, std::nullopt, {"k", "play", "f"}), doctest::Contains("nothing of model 'm' is left to export"),
                       UsageError);
}

}  // namespace prony_cards_test
