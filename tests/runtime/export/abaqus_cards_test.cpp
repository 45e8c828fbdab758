// The Abaqus material read back as Abaqus reads it (fe_card_reading.hpp): its Prony series is the
// model's storage and loss as `rheo simulate`'s harmonic path computes them.
#include "runtime/export/abaqus_cards.hpp"

#include "fe_card_reading.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <string>

namespace abaqus_cards_test {

using namespace rheo;
namespace fe = runtime::fe;

namespace {

const fe::CardSource kSource{"bushing.rheo", "9.8.7"};

const char* kModel = R"(model bushing {
  spring eq (k = 250 N/mm)
  maxwell m1 (k = 700 N/mm, tau = 0.8 ms)
  maxwell m2 (k = 90 N/mm, tau = 40 ms)
  series slow { spring s (k = 35 N/mm)  dashpot d (c = 70 N*s/mm) }
  springpot sp (k = 40 N/mm, alpha = 0.2, tau = 0.01 s, f_low = 0.1 Hz, f_high = 100 Hz)
})";

// Storage and loss [N/mm] of the harmonic protocol at f.
std::complex<double> simulated(const runtime::Network& network, double frequency) {
  const auto p = runtime::simulate_harmonic_point(network, 1.0, frequency, runtime::HarmonicOptions{});
  return {p.measures.storage, p.measures.loss};
}

void check_against_simulation(const runtime::Network& network, const test::ReadMaterial& m, double modulus_per_stiffness, double tolerance) {
  for (double f : {1e-3, 0.05, 1.0, 7.0, 60.0, 500.0, 1e5}) {
    const auto cards = test::complex_young(m, f) / modulus_per_stiffness;
    const auto sim = simulated(network, f);
    CHECK(std::abs(cards.real() / sim.real() - 1.0) <= tolerance);
    CHECK(std::abs(cards.imag() / sim.imag() - 1.0) <= tolerance);
  }
}

}  // namespace

TEST_CASE("abaqus cards: *ELASTIC, MODULI=INSTANTANEOUS and *VISCOELASTIC, TIME=PRONY give the simulated storage and loss") {
  const auto network = test::network_from(kModel, "bushing");
  const auto cards = fe::prony_cards(network, std::nullopt, {});
  const std::string text = fe::abaqus_material(cards, {}, kSource);
  const auto m = test::read_abaqus(text);
  CHECK(m.instantaneous_moduli);
  CHECK(m.poisson == 0.49);
  REQUIRE(m.terms.size() == 3 + cards.springpots.at(0).modes);
  for (const auto& t : m.terms) CHECK(t.bulk == t.shear);  // bulk and shear relax alike
  CHECK(text.find("*MATERIAL, NAME=bushing\n") != std::string::npos);
  check_against_simulation(network, m, 1.0, 1e-12);
}

TEST_CASE("abaqus cards: with a geometry the cards are moduli, M = K h / A, and the header says so") {
  const auto network = test::network_from(kModel, "bushing");
  const auto cards = fe::prony_cards(network, fe::Geometry{314.0, 10.0, "m.rheo:9:8"}, {});
  const std::string text = fe::abaqus_material(cards, {}, kSource);
  check_against_simulation(network, test::read_abaqus(text), 10.0 / 314.0, 1e-12);
  CHECK(text.find("** Specimen geometry from m.rheo:9:8: area A = 314 mm^2, height h = 10 mm.") != std::string::npos);
  CHECK(text.find("Units: N, mm, s.") != std::string::npos);
}

TEST_CASE("abaqus cards: --modulus shear writes E_0 = 2 (1 + nu) G_0") {
  const auto network = test::network_from(kModel, "bushing");
  const auto cards = fe::prony_cards(network, std::nullopt, {});
  const auto m = test::read_abaqus(fe::abaqus_material(cards, {fe::ModulusKind::shear, 0.3}, kSource));
  CHECK(m.poisson == 0.3);
  check_against_simulation(network, m, 2.0 * 1.3, 1e-12);
}

TEST_CASE("abaqus cards: the header names the model, the rheo version, the source and each element's terms") {
  const auto network = test::network_from(kModel, "bushing");
  const std::string text = fe::abaqus_material(fe::prony_cards(network, std::nullopt, {}), {}, kSource);
  CHECK(text.starts_with("** Abaqus material of model 'bushing' from bushing.rheo, written by rheo 9.8.7 (rheo export).\n"));
  CHECK(text.find("**   spring eq -> M_inf\n") != std::string::npos);
  CHECK(text.find("**   Maxwell element m1 (test.rheo:3:3) -> term 1\n") != std::string::npos);
  CHECK(text.find("**   Maxwell element slow.s (test.rheo:5:17) -> term 3\n") != std::string::npos);
  CHECK(text.find("**   springpot sp (test.rheo:6:3) -> terms 4-") != std::string::npos);
  CHECK(text.find("No specimen geometry") != std::string::npos);
  CHECK(text.find("nu = 0.49 is an assumption") != std::string::npos);
  // Every line before the cards is a comment.
  CHECK(text.substr(0, text.find("*MATERIAL")).find("\n*") == text.substr(0, text.find("*MATERIAL")).find("\n**"));
}

TEST_CASE("abaqus cards: a model of springs alone is an elastic material, without MODULI") {
  const auto network = test::network_from("model s { spring a (k = 100 N/mm) spring b (k = 20 N/mm) }", "s");
  const std::string text = fe::abaqus_material(fe::prony_cards(network, std::nullopt, {}), {}, kSource);
  CHECK(text.find("*ELASTIC\n120., 0.49\n") != std::string::npos);
  CHECK(text.find("\n*VISCOELASTIC") == std::string::npos);
}

}  // namespace abaqus_cards_test
