// The ANSYS commands read back as ANSYS reads them (fe_card_reading.hpp): MP,EX is the
// instantaneous modulus and the TB,PRONY SHEAR and BULK tables hold the model's relaxation.
#include "runtime/export/ansys_cards.hpp"

#include "fe_card_reading.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <string>

namespace ansys_cards_test {

using namespace rheo;
namespace fe = runtime::fe;

namespace {

const fe::CardSource kSource{"gel.rheo", "1.2.3"};

const char* kModel = R"(model gel {
  spring eq (k = 12 N/mm)
  springpot sp (k = 30 N/mm, alpha = 0.45, tau = 1 s, f_low = 0.01 Hz, f_high = 1000 Hz)
  maxwell m1 (k = 5 N/mm, tau = 2 s)
})";

}  // namespace

TEST_CASE("ansys cards: MP,EX and the TB,PRONY tables give the simulated storage and loss") {
  const auto network = test::network_from(kModel, "gel");
  const auto cards = fe::prony_cards(network, fe::Geometry{50.0, 2.0, "g"}, {});
  const std::string text = fe::ansys_material(cards, {}, kSource);
  const auto m = test::read_ansys(text);
  REQUIRE(m.terms.size() == cards.terms.size());
  CHECK(m.poisson == 0.49);
  for (const auto& t : m.terms) CHECK(t.bulk == t.shear);
  for (double f : {1e-3, 0.1, 3.0, 300.0, 1e4}) {
    const auto k = test::complex_young(m, f) * 50.0 / 2.0;
    const auto p = runtime::simulate_harmonic_point(network, 0.2, f, runtime::HarmonicOptions{});
    CHECK(std::abs(k.real() / p.measures.storage - 1.0) <= 1e-12);
    CHECK(std::abs(k.imag() / p.measures.loss - 1.0) <= 1e-12);
  }
  CHECK(text.starts_with("! ANSYS Mechanical APDL material of model 'gel' from gel.rheo, written by rheo 1.2.3 (rheo export).\n"));
  CHECK(text.find(fmt::format("TB,PRONY,RHEO_MAT,1,{},SHEAR\nTBDATA,1,", cards.terms.size())) != std::string::npos);
  CHECK(text.find("RHEO_MAT = 1") != std::string::npos);
}

TEST_CASE("ansys cards: more than 100 Prony pairs are refused at the springpot that makes them") {
  const auto network = test::network_from(
      "model wide {\n  spring eq (k = 1)\n  springpot sp (k = 3, alpha = 0.5, tau = 1 s, f_low = 1e-15 Hz, f_high = 1e15 Hz)\n}", "wide");
  const auto cards = fe::prony_cards(network, std::nullopt, {});
  REQUIRE(cards.terms.size() > fe::kAnsysMaxPronyPairs);
  CHECK_THROWS_WITH_AS(fe::ansys_material(cards, {}, kSource), doctest::Contains("test.rheo:3:3: error: model 'wide' makes"), ModelError);
  CHECK_THROWS_WITH_AS(fe::ansys_material(cards, {}, kSource), doctest::Contains("at most 100 pairs (springpot 'sp'"), ModelError);
}

}  // namespace ansys_cards_test
