// The structures of the model-order study (thesis Fig. 6.2): every combination of counts, the
// copies spread over the measured frequencies and amplitudes, the other elements kept.
#include "runtime/fit/order_study.hpp"

#include "lang/frontend.hpp"
#include "runtime/closed_form/periodic_closed_form.hpp"
#include "runtime/core/errors.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <numbers>

namespace order_study_test {

using namespace rheo;

namespace {
std::vector<runtime::FitDataSet> grid(double f_low, double f_high) {
  runtime::HarmonicData h;
  h.path = "g.csv";
  h.amplitude = {0.2, 2.0};
  h.frequency = {f_low, f_high};
  h.stiffness = {100.0, 100.0};
  h.phase = {0.1, 0.1};
  return {runtime::FitDataSet{"g.csv", 1.0, h, {}}};
}
const char* kModel =
    "model b {\n  spring k0 (k = 300 N/mm in [10, 3000])\n  maxwell m1 (k = 50 N/mm in [1, 1000], tau = 10 ms in [0.01, 1000])\n"
    "  friction f1 (k = 100 N/mm in [1, 1000], uy = 50 um in [0.1, 1000])\n}";
}  // namespace

TEST_CASE("order study: every count combination, copies spread over the data, each a model that compiles") {
  const lang::CheckedModel model = test::model_from(kModel, "b");
  const runtime::OrderStudy study(model, {runtime::CountRange{1, 3}, runtime::CountRange{2, 2}}, grid(1.0, 100.0));
  const auto variants = study.variants();
  REQUIRE(variants.size() == 3);
  CHECK(variants[0].maxwell == 1);
  CHECK(variants[2].maxwell == 3);
  CHECK(variants[2].friction == 2);
  for (const auto& v : variants) {
    const lang::Program program = lang::compile_source("v.rheo", v.source);
    const lang::CheckedModel* m = program.find_model("b");
    REQUIRE(m != nullptr);
    CHECK(m->root.children.size() == static_cast<std::size_t>(1 + v.maxwell + v.friction));  // k0 kept
    CAPTURE(v.source);
    CHECK(v.source.find("spring k0 (k = 300 N/mm in [10 N/mm, 3000 N/mm])") != std::string::npos);
  }
  // Three relaxation times log-even over 1/(2 pi f) for f from 100 Hz to 1 Hz.
  const lang::Program three = lang::compile_source("v.rheo", variants[2].source);
  const lang::CheckedModel& m3 = *three.find_model("b");
  auto value = [&](const std::string& path) {
    for (const auto& p : m3.parameters)
      if (p.path == path) return p.value;
    FAIL("no parameter " << path);
    return 0.0;
  };
  const double tau_low = 1.0 / (2.0 * std::numbers::pi * 100.0), tau_high = 1.0 / (2.0 * std::numbers::pi * 1.0);
  CHECK(value("order_m1.c") / value("order_m1.k") == doctest::Approx(tau_low).epsilon(1e-4).scale(0.0));
  CHECK(value("order_m2.c") / value("order_m2.k") == doctest::Approx(std::sqrt(tau_low * tau_high)).epsilon(1e-4).scale(0.0));
  CHECK(value("order_m3.c") / value("order_m3.k") == doctest::Approx(tau_high).epsilon(1e-4).scale(0.0));
}

TEST_CASE("order study: a model with a block, or without the element to copy, is refused with advice") {
  const lang::CheckedModel nested = test::model_from("model n { series { spring a (k = 1 N/mm in [0.1, 10]) spring b (k = 1 N/mm) } }", "n");
  CHECK_THROWS_WITH_AS(runtime::OrderStudy(nested, {runtime::CountRange{1, 2}, std::nullopt}, grid(1.0, 10.0)),
                       doctest::Contains("needs a model whose elements all act in parallel"), runtime::UsageError);
  const lang::CheckedModel plain = test::model_from("model p { spring a (k = 1 N/mm in [0.1, 10]) }", "p");
  CHECK_THROWS_WITH_AS(runtime::OrderStudy(plain, {std::nullopt, runtime::CountRange{1, 2}}, grid(1.0, 10.0)),
                       doctest::Contains("has no friction element to copy bounds from"), runtime::UsageError);
}

TEST_CASE("order study: a structure with one copy more starts from the fit of the one before, with the same response") {
  const lang::CheckedModel model = test::model_from(kModel, "b");
  const runtime::OrderStudy study(model, {runtime::CountRange{1, 2}, runtime::CountRange{2, 3}}, grid(1.0, 100.0));
  const auto variants = study.variants();
  REQUIRE(variants.size() == 4);  // (1, 2), (1, 3), (2, 2), (2, 3)
  auto index = [](const lang::CheckedModel& m, const std::string& path) {
    for (std::size_t i = 0; i < m.parameters.size(); ++i)
      if (m.parameters[i].path == path) return i;
    FAIL("no parameter " << path);
    return std::size_t{0};
  };
  const lang::Program two = lang::compile_source("two.rheo", variants[0].source);
  const lang::CheckedModel& before = *two.find_model("b");
  // "Fitted" values of the (1, 2) structure (fy = k uy and c = k tau derived by the network).
  std::vector<double> fitted;
  for (const auto& p : before.parameters) fitted.push_back(p.value);
  fitted[index(before, "k0.k")] = 420.0;
  fitted[index(before, "order_m1.k")] = 77.0, fitted[index(before, "order_m1.tau")] = 0.02;
  fitted[index(before, "order_f1.k")] = 200.0, fitted[index(before, "order_f1.uy")] = 0.01;
  fitted[index(before, "order_f2.k")] = 50.0, fitted[index(before, "order_f2.uy")] = 0.1;
  const runtime::Network fitted_network = runtime::Network::compile(before).with_parameters(fitted);
  fitted = fitted_network.parameters();
  for (std::size_t next : {1u, 2u}) {  // one friction element more; one Maxwell element more
    CAPTURE(next);
    const lang::Program program = lang::compile_source("next.rheo", variants[next].source);
    const lang::CheckedModel& after = *program.find_model("b");
    const std::vector<double> start = study.warm_start(after, before, fitted);
    REQUIRE(start.size() == after.parameters.size());
    CHECK(start[index(after, "k0.k")] == 420.0);
    if (next == 1) {
      // The stiffest friction copy (f1) and the new one share f1's fit: half its k each, its uy.
      CHECK(start[index(after, "order_f1.k")] == doctest::Approx(100.0));
      CHECK(start[index(after, "order_f3.k")] == doctest::Approx(100.0));
      CHECK(start[index(after, "order_f3.uy")] == doctest::Approx(0.01).scale(0.0));
      CHECK(start[index(after, "order_f2.k")] == 50.0);
    } else {
      CHECK(start[index(after, "order_m1.k")] == doctest::Approx(38.5));
      CHECK(start[index(after, "order_m2.k")] == doctest::Approx(38.5));
      CHECK(start[index(after, "order_m2.tau")] == doctest::Approx(0.02).scale(0.0));
    }
    // The same response as the fitted structure, at every amplitude and frequency.
    const runtime::Network warm = runtime::Network::compile(after).with_parameters(start);
    for (double u0 : {0.005, 0.05, 1.0})
      for (double f : {0.5, 20.0}) {
        const auto a = runtime::closed_form_harmonic_point(fitted_network, u0, f, runtime::HarmonicDefinition::thesis);
        const auto b = runtime::closed_form_harmonic_point(warm, u0, f, runtime::HarmonicDefinition::thesis);
        CHECK(b.measures.stiffness == doctest::Approx(a.measures.stiffness).epsilon(1e-12));
        CHECK(b.measures.phase == doctest::Approx(a.measures.phase).epsilon(1e-12).scale(0.0));
      }
  }
}

}  // namespace order_study_test
