// Root elements written back as statements (element_text.hpp): compiled again they have the same
// parameters at the same values, free ones with their bounds, under the same paths; a split
// writes one-sided caps around the cap; elements that cannot be written give nothing.
#include "runtime/diagnosis/element_text.hpp"
#include "runtime/protocols/harmonic.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

#include <fmt/format.h>

#include <map>
#include <string>
#include <vector>

namespace element_text_test {

using namespace rheo;
namespace dx = runtime::diagnosis;

namespace {

const char* kModel = R"(model m {
  spring s (k = 35.5 N/mm in [1, 1000])
  maxwell r (k = 12 N/mm, tau = 40 ms in [1, 1000])
  series b {
    gap g (width = 2 mm in [0.1, 10], center = 0.25 mm)
    friction f (k = 400 N/mm in [1, 10000], uy = 30 um in [1, 1000])
    parallel p { slider c (fy = 20 N)  spring k (k = 5 N/mm) }
  }
  friction a (k = 100 N/mm, fy_pos = 30 N, fy_neg = 20 N in [1, 100])
}
)";

std::map<std::string, lang::Parameter> by_path(const lang::CheckedModel& model) {
  std::map<std::string, lang::Parameter> out;
  for (const auto& p : model.parameters) out[p.path] = p;
  return out;
}

}  // namespace

TEST_CASE("element_text: every root element compiles back to its parameters, values, bounds and paths") {
  const runtime::Network network = test::network_from(kModel, "m");
  std::string body;
  int free = 0, caps = 0;
  for (const lang::Element& e : network.model().root.children) {
    const auto text = dx::element_text(network, e);
    REQUIRE(text.has_value());
    body += dx::joined(*text) + "\n";
    free += text->free, caps += text->symmetric_caps;
  }
  CHECK(free == 6);  // s.k, r.tau, g.width, f.k, f.uy, a.fy_neg
  CHECK(caps == 2);  // f and the slider c; a is one-sided already
  const auto original = by_path(network.model());
  const auto again = by_path(test::model_from("model m {\n" + body + "}\n", "m"));
  REQUIRE(again.size() == original.size());
  for (const auto& entry : original) {
    const auto& path = entry.first;  // not a structured binding: Clang 14 cannot capture one
    const auto& p = entry.second;
    CAPTURE(path);
    REQUIRE(again.count(path) == 1);
    const lang::Parameter& q = again.at(path);
    CHECK(q.value == doctest::Approx(p.value).epsilon(1e-11).scale(0.0));
    CHECK(q.free == p.free);
    if (p.free) {
      CHECK(q.lower == doctest::Approx(p.lower).epsilon(1e-8).scale(0.0));
      CHECK(q.upper == doctest::Approx(p.upper).epsilon(1e-8).scale(0.0));
    }
  }
}

TEST_CASE("element_text: a split writes every one-cap yield as fy_pos = fy (1 + split), fy_neg = fy (1 - split)") {
  const runtime::Network network = test::network_from(kModel, "m");
  const lang::Element& b = network.model().root.children[2];
  const auto text = dx::element_text(network, b, 0.25);
  REQUIRE(text.has_value());
  const auto split = by_path(test::model_from("model m {\n" + dx::joined(*text) + "\n}\n", "m"));
  CHECK(split.at("b.f.fy_pos").value == doctest::Approx(12.0 * 1.25));  // fy = k uy = 12 N
  CHECK(split.at("b.f.fy_neg").value == doctest::Approx(12.0 * 0.75));
  CHECK(split.at("b.f.fy_pos").free);
  CHECK(split.at("b.p.c.fy_pos").value == doctest::Approx(25.0));
  CHECK(split.at("b.p.c.fy_neg").value == doctest::Approx(15.0));
  CHECK(split.at("b.g.width").value == doctest::Approx(2.0));
  CHECK(split.count("b.f.uy") == 0);
}

TEST_CASE("element_text: an element with a quadratic dashpot or Bouc-Wen element cannot be written") {
  const runtime::Network network = test::network_from(
      "model q { series c { spring k (k = 1 N/mm)  quadratic_dashpot d (cq = 1 N*s^2/mm^2) }  bouc_wen w (k = 1 N/mm, fy = 1 N, n = 2) }", "q");
  for (const lang::Element& e : network.model().root.children) CHECK_FALSE(dx::element_text(network, e).has_value());
}

// The mirror symmetry the backlash family leans on (element_text.hpp play_biases): play centred
// at -c in front of a mirror-symmetric element scores as play at +c on harmonic points about zero
// (same stiffness and phase, here by the event path at amplitudes inside, across and beyond the
// play). A friction element with one-sided caps is no mirror image of itself (the mirror swaps
// its caps): play in front of it is tried both ways.
TEST_CASE("gapped_element_family: harmonic points about zero see play at -c as at +c, so only one is tried") {
  auto point = [](const std::string& element, double center, double amplitude, double frequency) {
    const runtime::Network n = test::network_from(
        fmt::format("model p {{ series b {{ gap g (width = 0.6 mm, center = {} mm)  {} }} }}", center, element), "p");
    return runtime::simulate_harmonic_point(n, amplitude, frequency, runtime::HarmonicOptions{});
  };
  for (const char* element : {"spring e (k = 300 N/mm)", "maxwell e (k = 300 N/mm, tau = 5 ms)", "friction e (k = 300 N/mm, uy = 40 um)"})
    for (double amplitude : {0.2, 0.45, 1.5})
      for (double frequency : {1.0, 30.0}) {
        CAPTURE(element);
        CAPTURE(amplitude);
        CAPTURE(frequency);
        const runtime::HarmonicPoint plus = point(element, 0.15, amplitude, frequency), minus = point(element, -0.15, amplitude, frequency);
        CHECK(minus.measures.stiffness == doctest::Approx(plus.measures.stiffness).epsilon(1e-9));
        CHECK(minus.measures.phase == doctest::Approx(plus.measures.phase).epsilon(1e-9).scale(1.0));  // [rad], near 0 for the spring
      }
  const runtime::Network network = test::network_from(kModel, "m");
  auto biases = [&](bool symmetric_drives, const std::string& element) {
    std::vector<double> out;
    for (const dx::Trial& t : dx::gapped_element_family(network, {0.1, 1.0}, symmetric_drives))
      if (t.replaces == element && t.slip == 0.1) out.push_back(t.bias);
    return out;
  };
  CHECK(biases(false, "s") == std::vector<double>{-0.5, 0.0, 0.5});
  CHECK(biases(true, "s") == std::vector<double>{0.0, 0.5});
  CHECK(biases(true, "r") == std::vector<double>{0.0, 0.5});
  CHECK(biases(true, "a") == std::vector<double>{-0.5, 0.0, 0.5});  // one-sided caps
}

}  // namespace element_text_test
