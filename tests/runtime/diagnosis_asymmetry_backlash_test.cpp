// rheo diagnose names the effects of issue 24 hidden in measured histories (noise as in
// diagnosis_support.hpp: force + 0.003 max|F| N(0,1)): a yield force that differs in tension and
// compression, a stiffness with an even power, and free play off-centre, each diagnosed from a
// model without it; and `asymmetry` is not offered where the data cannot show it (harmonic
// tables only).
#include "runtime/diagnosis/candidate_model.hpp"
#include "runtime/diagnosis/diagnose.hpp"
#include "runtime/diagnosis/screen.hpp"

#include "diagnosis_generator.hpp"
#include "diagnosis_support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace diagnosis_asymmetry_backlash_test {

using namespace rheo;
namespace dx = runtime::diagnosis;
using test::diagnose;
using test::history_measurement;
namespace gen = test::generated;

namespace {

std::string candidates(const dx::Diagnosis& d) {
  std::string out;
  for (const auto& c : d.candidates)
    out += fmt::format(
        "\n  {:28} gain {:.3f}  {}", dx::effect_name(c.screened.effect), c.screened.gain,
        c.refitted ? fmt::format("gap {:.4g} p {} in {:.1f} s", c.gap_after, c.parameters, c.wall_seconds) : std::string("not refitted"));
  return out;
}

void require_effect(const dx::Diagnosis& d, dx::Effect effect) {
  MESSAGE("named " << dx::effect_name(d.effect) << ", gap " << d.gap_before << " -> " << d.gap_after << candidates(d));
  INFO("named " << dx::effect_name(d.effect) << ": " << d.reason);
  CHECK(dx::effect_name(d.effect) == dx::effect_name(effect));
  CHECK(d.gap_after <= d.gap_before / 3.0);
  CHECK(d.refined_text.find("added by rheo diagnose: " + std::string(dx::effect_name(effect))) != std::string::npos);
}

const char* kStart = "model start {\n  spring s (k = 300 N/mm in [10, 10000])\n  friction f (k = 100 N/mm in [1, 10000], uy = 20 um in [0.1, 10000])\n}\n";

}  // namespace

TEST_CASE("diagnose, sine history: yield forces of 30 N in tension and 60 N in compression are asymmetry") {
  const std::string truth = "model truth { spring s (k = 250 N/mm)  friction f (k = 400 N/mm, fy_pos = 30 N, fy_neg = 60 N) }";
  const dx::Diagnosis d = diagnose(kStart, {history_measurement(truth, runtime::quasistatic_sine({1.0, 0.5}, 0.5, 2, 200), 31)});
  require_effect(d, dx::Effect::asymmetry);
}

TEST_CASE("diagnose, static loops: a stiffness with an even power is asymmetry") {
  const std::string truth = "model truth { poly_spring s (k1 = 250 N/mm, k2 = 60 N/mm^2)  friction f (k = 300 N/mm, uy = 50 um) }";
  const dx::Diagnosis d = diagnose(kStart, {history_measurement(truth, runtime::static_triangle({2.0, 1.0}, 0.5, 1, 400), 32)});
  require_effect(d, dx::Effect::asymmetry);
}

TEST_CASE("diagnose, static loops: a spring behind off-centre free play is backlash") {
  const std::string truth = R"(model truth { spring s (k = 200 N/mm)  friction f (k = 300 N/mm, uy = 50 um)
                               series b { gap g (width = 1 mm, center = 0.3 mm)  spring k (k = 600 N/mm) } })";
  const dx::Diagnosis d = diagnose(kStart, {history_measurement(truth, runtime::static_triangle({2.0, 1.0}, 0.5, 1, 400), 33)});
  require_effect(d, dx::Effect::backlash);
}

TEST_CASE("asymmetry is screened on histories only, backlash on harmonic tables too") {
  runtime::HarmonicData h;
  h.amplitude = {0.1, 1.0}, h.frequency = {1.0, 1.0}, h.stiffness = {100.0, 90.0}, h.phase = {0.1, 0.1}, h.rows = {2, 3};
  const std::vector<runtime::FitDataSet> harmonic{{"h.csv", 1.0, h}};
  const dx::DataScales scales = dx::data_scales(harmonic);
  CHECK_FALSE(scales.has_history);
  CHECK_FALSE(dx::trial_family(dx::Effect::backlash, scales, "").empty());
  for (const dx::Trial& t : dx::trial_family(dx::Effect::asymmetry, scales, "s")) CHECK(t.shape == dx::Shape::even_spring);
  runtime::HistoryData r;
  r.drive = runtime::quasistatic_sine({1.0}, 1.0, 1, 40);
  r.force.assign(r.drive.time.size(), 1.0), r.rows.assign(r.force.size(), 0), r.force_scale = 1.0;
  const dx::DataScales with_history = dx::data_scales({{"r.csv", 1.0, r}});
  CHECK(with_history.has_history);
  const auto family = dx::trial_family(dx::Effect::asymmetry, with_history, "s");
  CHECK(std::any_of(family.begin(), family.end(), [](const dx::Trial& t) { return t.shape == dx::Shape::asymmetric_friction; }));
}

// On a harmonic table the measures are even in the play's centre: at a centred start its
// column is zero and, at any start, nearly so where both sides engage. The refit's searches
// once stalled there (every damped step sent the centre across its box; levenberg_marquardt
// holds such a parameter now) and left the spring behind the play where the screen put it.
TEST_CASE("diagnose, harmonic table: a spring behind off-centre free play is backlash") {
  const std::string truth = R"(model truth { spring s (k = 200 N/mm)  friction f (k = 300 N/mm, uy = 50 um)
                               series b { gap g (width = 1 mm, center = 0.3 mm)  spring k (k = 600 N/mm) } })";
  const dx::Diagnosis d = diagnose(kStart, {test::harmonic_measurement(truth, 34, {0.05, 0.1, 0.2, 0.3, 0.45, 0.6, 0.8, 1.0, 1.5, 2.0})});
  require_effect(d, dx::Effect::backlash);
}

// Play that closes only at the top amplitude (half-width 1.7 mm, centre 0.1 mm: between the two
// largest amplitudes, 1.6 and 2 mm) behind a spring 15 times the model's: at 2 mm the spring adds
// about 7 % of its k. The screen sized it with k at most 3 times the measured stiffness and
// ranked it below a yeoh spring (0.35 against 0.39); sized by the stiffness it adds where it
// engages, it leads, and its refit takes the gap from 0.087 to 0.023.
TEST_CASE("diagnose, harmonic table: free play that closes only at the top amplitude is backlash, screened first") {
  const std::string truth = R"(model truth { spring s (k = 200 N/mm)  friction f (k = 300 N/mm, uy = 50 um)
                               series b { gap g (width = 3.4 mm, center = 0.1 mm)  spring k (k = 3000 N/mm) } })";
  const dx::Diagnosis d = diagnose(kStart, {test::harmonic_measurement(truth, 35, {0.05, 0.1, 0.2, 0.5, 1.0, 1.6, 2.0})});
  require_effect(d, dx::Effect::backlash);
  REQUIRE_FALSE(d.candidates.empty());
  CHECK(dx::effect_name(d.candidates.front().screened.effect) == dx::effect_name(dx::Effect::backlash));
}

// A model with free play fitted to a table where the search ends with the play's centre beyond
// half its width (0.1 mm wide, centred at -0.66 mm: it acts as the stop touching at rest, centred
// at -0.05 mm). The fitted source was written with that centre, which a .rheo file refuses
// (`|center| <= width/2`): every candidate built on it threw. It is written now as the play it
// acts as (candidate_model.hpp with_gaps_in_play), as the refitted candidates are.
TEST_CASE("diagnose: a start model whose fitted play ends centred beyond half its width is written as the play it acts as") {
  const gen::Scenario sc = gen::harmonic_scenario(7, gen::Hidden::play);
  std::string start = sc.start;
  start.insert(
      start.rfind('}'),
      "  series b { gap g (width = 0.4752 mm in [0.001, 3], center = -0.0264 mm in [-1.3, 1.3])  spring k (k = 704.6 N/mm in [1, 10000]) }\n");
  const dx::Diagnosis d = diagnose(start, sc.data, false, 0);
  const runtime::Network& fitted = d.before.network;
  const double width = fitted.parameter(dx::parameter_index(fitted.model(), "b.g.width"));
  const double center = fitted.parameter(dx::parameter_index(fitted.model(), "b.g.center"));
  CHECK(std::abs(center) <= width / 2.0);
}

}  // namespace diagnosis_asymmetry_backlash_test
