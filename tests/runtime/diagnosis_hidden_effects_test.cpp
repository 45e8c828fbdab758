// rheo diagnose on measurements in which one effect is hidden: data simulated from a richer
// model with the noise of examples/data (stiffness x (1 + 0.01 N(0,1)), phase + 0.15 deg
// N(0,1); histories: force + 0.003 max|F| N(0,1)), diagnosed from a model that lacks the
// effect. Each case requires the effect's name and err_after <= err_before / 3; data the
// start model already explains must give `none` with nothing added. The hidden models vary in
// values and in which branch carries the effect, so that no threshold is tuned to one case.
#include "runtime/diagnosis/diagnose.hpp"
#include "runtime/diagnosis/diagnosis_report.hpp"
#include "runtime/fit/objective.hpp"

#include "diagnosis_support.hpp"
#include "runtime/protocols/run_history.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <numbers>
#include <random>

namespace diagnosis_hidden_effects_test {

using namespace rheo;
namespace dx = runtime::diagnosis;
using test::diagnose;
using test::harmonic_measurement;
using test::history_measurement;

namespace {

// Every candidate's screening and refit, for the failure message.
std::string candidates(const dx::Diagnosis& d) {
  std::string out;
  for (const auto& c : d.candidates)
    out += fmt::format("\n  {:28} gain {:.3f}  {}", dx::effect_name(c.screened.effect), c.screened.gain,
                       c.refitted ? fmt::format("gap {:.4g} BIC {:.1f} p {} in {:.1f} s", c.gap_after, c.criterion, c.parameters, c.wall_seconds)
                                  : std::string("not refitted"));
  return out;
}

void require_effect(const dx::Diagnosis& d, dx::Effect effect) {
  MESSAGE("named " << dx::verdict_name(d) << ", gap " << d.gap_before << " -> " << d.gap_after << " (noise floor " << d.noise.floor << " +- "
                   << d.noise.relative_error << ", ratio " << d.noise_ratio << "); candidates (BIC before " << d.criterion_before
                   << "):" << candidates(d));
  INFO("named " << dx::verdict_name(d) << ": " << d.reason);
  INFO("gap " << d.gap_before << " -> " << d.gap_after);
  CHECK(dx::effect_name(d.effect) == dx::effect_name(effect));
  CHECK(d.gap_after <= d.gap_before / 3.0);
  CHECK(!d.added_element.empty());
  CHECK(d.refined_text.find("added by rheo diagnose: " + std::string(dx::effect_name(effect))) != std::string::npos);
}

// History cases also require the refined model to reach the noise: the force noise (0.003
// max|F|) sets the RMS force residual a right model leaves, so 0.0036 allows 20 % for the fit.
void require_noise_floor(const dx::Diagnosis& d) { CHECK(d.gap_after <= 1.2 * 0.003); }

void require_none(const dx::Diagnosis& d) {
  MESSAGE("named " << dx::effect_name(d.effect) << ", gap " << d.gap_before << " -> " << d.gap_after << "; candidates (BIC before "
                   << d.criterion_before << "):" << candidates(d));
  INFO("named " << dx::effect_name(d.effect) << ": " << d.reason);
  CHECK(d.effect == dx::Effect::none);
  CHECK(d.added_element.empty());
  CHECK(!d.after);
  CHECK(d.gap_after == d.gap_before);
}


}  // namespace

TEST_CASE("diagnose, harmonic: a missing friction element is amplitude-dependence") {
  const std::string truth = "model truth { spring s (k = 600 N/mm)  maxwell m (k = 120 N/mm, tau = 4 ms)  friction f (k = 400 N/mm, uy = 30 um) }";
  const std::string start =
      "model start {\n  spring s (k = 500 N/mm in [10, 10000])\n  maxwell m (k = 100 N/mm in [1, 10000], tau = 10 ms in [0.01, 10000])\n}\n";
  require_effect(diagnose(start, {harmonic_measurement(truth, 1)}), dx::Effect::amplitude_dependence);
}

TEST_CASE("diagnose, harmonic: a second, large-slip friction element hidden beside one is amplitude-dependence") {
  const std::string truth = R"(model truth { spring s (k = 300 N/mm)  maxwell m (k = 80 N/mm, tau = 20 ms)
                               friction f1 (k = 150 N/mm, uy = 20 um)  friction f2 (k = 400 N/mm, uy = 400 um) })";
  const std::string start = R"(model start {
  spring s (k = 300 N/mm in [10, 10000])
  maxwell m (k = 80 N/mm in [1, 10000], tau = 20 ms in [0.01, 10000])
  friction f1 (k = 200 N/mm in [1, 10000], uy = 30 um in [0.1, 10000])
}
)";
  require_effect(diagnose(start, {harmonic_measurement(truth, 2)}), dx::Effect::amplitude_dependence);
}

TEST_CASE("diagnose, harmonic: a missing Maxwell element is rate-dependence") {
  const std::string truth = "model truth { spring s (k = 500 N/mm)  friction f (k = 300 N/mm, uy = 50 um)  maxwell m (k = 250 N/mm, tau = 3 ms) }";
  const std::string start =
      "model start {\n  spring s (k = 500 N/mm in [10, 10000])\n  friction f (k = 100 N/mm in [1, 10000], uy = 20 um in [0.1, 10000])\n}\n";
  require_effect(diagnose(start, {harmonic_measurement(truth, 3)}), dx::Effect::rate_dependence);
}

TEST_CASE("diagnose, harmonic: a second relaxation time hidden beside one is rate-dependence") {
  const std::string truth = R"(model truth { spring s (k = 400 N/mm)  maxwell slow (k = 150 N/mm, tau = 40 ms)
                               maxwell fast (k = 300 N/mm, tau = 1.5 ms)  friction f (k = 100 N/mm, uy = 40 um) })";
  const std::string start = R"(model start {
  spring s (k = 400 N/mm in [10, 10000])
  maxwell m (k = 100 N/mm in [1, 10000], tau = 10 ms in [0.01, 10000])
  friction f (k = 100 N/mm in [1, 10000], uy = 40 um in [0.1, 10000])
}
)";
  require_effect(diagnose(start, {harmonic_measurement(truth, 4)}), dx::Effect::rate_dependence);
}

// The measured phases stay above 5 deg (two Maxwell elements), so that the phase noise does not
// set the floor of err (6.1): here about 0.003, against 0.06 for the linear model. (With phases
// down to 0.3 deg, 0.15 deg of noise alone gives err ~ 0.03, and no model is 3 times better.)
TEST_CASE("diagnose, harmonic: stiffening at large amplitude is nonlinear-elasticity") {
  const std::string truth = R"(model truth { yeoh r (D10 = 200 N/mm, D20 = 5 N/mm^3, D30 = 0.3 N/mm^5)  maxwell m (k = 300 N/mm, tau = 3 ms)
                               maxwell n (k = 300 N/mm, tau = 60 ms)  friction f (k = 150 N/mm, uy = 40 um) })";
  const std::string start = R"(model start {
  spring r (k = 400 N/mm in [10, 10000])
  maxwell m (k = 100 N/mm in [1, 10000], tau = 10 ms in [0.01, 10000])
  maxwell n (k = 100 N/mm in [1, 10000], tau = 100 ms in [0.01, 10000])
  friction f (k = 100 N/mm in [1, 10000], uy = 20 um in [0.1, 10000])
}
)";
  require_effect(diagnose(start, {harmonic_measurement(truth, 5, {0.1, 0.3, 1.0, 2.0, 3.0, 4.0})}), dx::Effect::nonlinear_elasticity);
}

TEST_CASE("diagnose, harmonic: a slider-capped Maxwell branch is coupled-amplitude-frequency") {
  const std::string truth = R"(model truth { spring s (k = 500 N/mm)  maxwell m (k = 100 N/mm, tau = 3 ms)
                               series b { slider cap (fy = 40 N)  maxwell arm (k = 400 N/mm, tau = 10 ms) } })";
  const std::string start = R"(model start {
  spring s (k = 500 N/mm in [10, 10000])
  maxwell m (k = 100 N/mm in [1, 10000], tau = 3 ms in [0.01, 10000])
  friction f (k = 100 N/mm in [1, 10000], uy = 50 um in [0.1, 10000])
}
)";
  const dx::Diagnosis d = diagnose(start, {harmonic_measurement(truth, 6)});
  require_effect(d, dx::Effect::coupled_amplitude_frequency);
  // No inertia hides here: the screened fluid column refits its resonance out of the band, and
  // its limit without inertia, the true shape, is the candidate that earns.
  const auto chosen = std::find_if(d.candidates.begin(), d.candidates.end(), [](const dx::CandidateOutcome& c) { return c.chosen; });
  REQUIRE(chosen != d.candidates.end());
  CHECK(chosen->screened.trial.shape == dx::Shape::capped_maxwell);
  CHECK(chosen->limit_of.find("limit without inertia") != std::string::npos);
  CHECK(dx::diagnosis_report_text("start.rheo", d).find("also tried as a slider") != std::string::npos);
  CHECK(dx::diagnosis_report_json("start.rheo", d, "").find("\"limit_of\"") != std::string::npos);
}

TEST_CASE("diagnose, harmonic: a hydromount's slider-capped fluid column is coupled-amplitude-frequency") {
  // The resonance sqrt((k1 + k2)/b)/2pi = 22.5 Hz lies inside the data; the cap slips above ~0.1 mm.
  const std::string truth = R"(model truth { spring rubber (k = 600 N/mm)  maxwell m (k = 150 N/mm, tau = 5 ms)
                               series fluid { slider cap (fy = 30 N)  spring chamber (k = 400 N/mm)
                                              parallel y { inerter column (b = 25 kg)  dashpot channel (c = 1.2 N*s/mm)  spring bulge (k = 100 N/mm) } } })";
  const std::string start = R"(model start {
  spring rubber (k = 500 N/mm in [10, 10000])
  maxwell m (k = 100 N/mm in [1, 10000], tau = 10 ms in [0.01, 10000])
  friction f (k = 100 N/mm in [1, 10000], uy = 50 um in [0.1, 10000])
}
)";
  const runtime::FitDataSet data = harmonic_measurement(truth, 13);
  const dx::Diagnosis d = diagnose(start, {data});
  require_effect(d, dx::Effect::coupled_amplitude_frequency);
  // The column alone cannot hold the stiffness its node rests on (the walls' 100 N/mm): with the
  // walls' spring the refined model reaches the noise, the err (6.1) of the generating model
  // itself on these data (its exact periodic state, an independent path to the floor).
  const runtime::Network generating = test::network_from(truth, "truth");
  const double floor = runtime::thesis_err(
      runtime::relative_residuals(data.harmonic(), runtime::simulate_at(generating, data.harmonic(), test::simulation_options())));
  MESSAGE("the generating model's err (6.1) on the data: " << floor);
  CHECK(d.gap_after <= 1.05 * floor);
  CHECK(d.refined_text.find("spring  bulge") != std::string::npos);
}

// Two Maxwell elements keep every measured phase above a few degrees, so that the phase noise
// leaves err (6.1) at 0.0034 for the true structure (with one, phases near 1 deg put that floor
// at 0.028, and no model can be 3 times better than the start).
TEST_CASE("diagnose, harmonic: a column resonating at 12 Hz beside two Maxwell elements is inertia") {
  const std::string truth = R"(model truth { spring s (k = 600 N/mm)  maxwell m (k = 250 N/mm, tau = 3 ms)  maxwell n (k = 150 N/mm, tau = 40 ms)
                               series c { spring k1 (k = 150 N/mm)  parallel y { inerter b (b = 25 kg)  dashpot d (c = 0.6 N*s/mm) } } })";
  const std::string start = R"(model start {
  spring s (k = 500 N/mm in [10, 10000])
  maxwell m (k = 100 N/mm in [1, 10000], tau = 10 ms in [0.01, 10000])
  maxwell n (k = 100 N/mm in [1, 10000], tau = 100 ms in [0.01, 10000])
}
)";
  require_effect(diagnose(start, {harmonic_measurement(truth, 14)}), dx::Effect::inertia);
}

TEST_CASE("diagnose, harmonic: a resonant column is inertia") {
  const std::string truth = R"(model truth { spring s (k = 500 N/mm)  friction f (k = 200 N/mm, uy = 50 um)
                               series c { spring k1 (k = 300 N/mm)  parallel y { inerter b (b = 20 kg)  dashpot d (c = 1 N*s/mm) } } })";
  const std::string start =
      "model start {\n  spring s (k = 500 N/mm in [10, 10000])\n  friction f (k = 100 N/mm in [1, 10000], uy = 20 um in [0.1, 10000])\n}\n";
  require_effect(diagnose(start, {harmonic_measurement(truth, 7)}), dx::Effect::inertia);
}

// A mass the drive moves (b = 28 kg against ~800 N/mm: resonance 27 Hz): above it the storage
// stiffness is negative and the phase beyond 90 deg, which eq. 5.1 compares with its sign.
TEST_CASE("diagnose, harmonic: a mass moved past its resonance is inertia, and the refit finds its inertance") {
  const std::string truth = "model truth { spring s (k = 700 N/mm)  maxwell m (k = 150 N/mm, tau = 4 ms)  inerter mass (b = 28 kg) }";
  const std::string start =
      "model start {\n  spring s (k = 500 N/mm in [10, 10000])\n  maxwell m (k = 100 N/mm in [1, 10000], tau = 10 ms in [0.01, 10000])\n}\n";
  const runtime::FitDataSet data = harmonic_measurement(truth, 21);
  CHECK(*std::max_element(data.harmonic().phase.begin(), data.harmonic().phase.end()) > std::numbers::pi / 2);
  const dx::Diagnosis d = diagnose(start, {data});
  require_effect(d, dx::Effect::inertia);
  const auto chosen = std::find_if(d.candidates.begin(), d.candidates.end(), [](const dx::CandidateOutcome& c) { return c.chosen; });
  REQUIRE(chosen != d.candidates.end());
  CHECK(chosen->screened.trial.shape == dx::Shape::mass);
}

// A model with the structure of the data's: nothing is missing.
using test::kExplainedStart;
using test::kExplainedTruth;

TEST_CASE("diagnose, harmonic: data the model already explains gives none") {
  const dx::Diagnosis d = diagnose(kExplainedStart, {harmonic_measurement(kExplainedTruth, 8)});
  require_none(d);
  // The verdict none is the noise's: estimated near the injected 1 % and 0.15 deg, the gap at it.
  CHECK(d.verdict == dx::Verdict::none);
  REQUIRE(d.noise.estimated);
  CHECK(d.noise.stiffness == doctest::Approx(0.01).epsilon(0.3).scale(0.0));
  CHECK(d.noise.phase * 180.0 / std::numbers::pi == doctest::Approx(0.15).epsilon(0.3).scale(0.0));
  CHECK(d.noise_ratio == doctest::Approx(1.0).epsilon(0.3).scale(0.0));
  CHECK(dx::diagnosis_report_json("start.rheo", d, "").find("\"noise\": {") != std::string::npos);
}

// Err (6.1) weighs a damping term by 1/sin(phase), so the noise of a few nearly elastic points
// dominates it, and a candidate that bends the model through them lowers the gap by 40 % on pure
// noise (4 of the 10 draws from seed 100 named an effect when the BIC was N ln(J) + p ln N).
// Under the noise-weighted criterion (criterion.hpp) no draw earns anything.
TEST_CASE("diagnose, harmonic: data the model already explains gives none over several noise draws") {
  // Under AddressSanitizer one draw (each several times the ~1.5 s here): the statistics are the Release run's.
  for (const unsigned seed : {100u, 101u, 102u}) {
    if (test::kUnderSanitizer && seed > 100u) break;
    CAPTURE(seed);
    const dx::Diagnosis d = diagnose(kExplainedStart, {harmonic_measurement(kExplainedTruth, seed)});
    require_none(d);
    CHECK(d.noise_weighted);
  }
}

// The false-positive rate on pure noise: of ten draws (five under AddressSanitizer, where each
// diagnosis takes several times the 1-15 s here), at most one may name an effect or call the
// residual unexplained. Judged on the fits of eq. 5.1, whose damping terms follow the phase noise
// of a few nearly elastic points, 3 of these 10 draws did (7 of the 40 from seed 100: a
// slider-capped Maxwell arm named, or a fit drawn to those points called unexplained at twice
// the noise floor); the likelihood at its maximum (criterion.hpp least_chi_square) leaves none.
TEST_CASE("diagnose, harmonic: pure noise rarely gives a verdict other than none") {
  int other = 0;
  std::string verdicts;
  for (unsigned seed = 117; seed < (test::kUnderSanitizer ? 122u : 127u); ++seed) {
    const dx::Diagnosis d = diagnose(kExplainedStart, {harmonic_measurement(kExplainedTruth, seed)});
    verdicts += fmt::format(" {}:{}", seed, dx::verdict_name(d));
    if (d.verdict != dx::Verdict::none) ++other;
  }
  INFO("verdicts:" << verdicts);
  CHECK(other <= 1);
}

TEST_CASE("diagnose, static loops: a Yeoh law behind the loops is nonlinear-elasticity") {
  const std::string truth = "model truth { yeoh r (D10 = 150 N/mm, D20 = -1 N/mm^3, D30 = 0.05 N/mm^5)  friction f (k = 200 N/mm, uy = 50 um) }";
  const std::string start =
      "model start {\n  spring r (k = 300 N/mm in [10, 10000])\n  friction f (k = 100 N/mm in [1, 10000], uy = 20 um in [0.1, 10000])\n}\n";
  const runtime::Drive drive = runtime::static_triangle({5.0, 2.5, 1.0}, 0.05, 1, 400);
  const dx::Diagnosis d = diagnose(start, {history_measurement(truth, drive, 9)});
  require_effect(d, dx::Effect::nonlinear_elasticity);
  require_noise_floor(d);
}

TEST_CASE("diagnose, quasi-static sine: a missing friction element is amplitude-dependence") {
  const std::string truth = "model truth { spring s (k = 300 N/mm)  maxwell m (k = 50 N/mm, tau = 0.5 s)  friction f (k = 300 N/mm, uy = 0.1 mm) }";
  const std::string start =
      "model start {\n  spring s (k = 300 N/mm in [10, 10000])\n  maxwell m (k = 50 N/mm in [1, 10000], tau = 100 ms in [0.01, 100000])\n}\n";
  const runtime::Drive drive = runtime::quasistatic_sine({2.0, 1.0, 0.5}, 0.1, 2, 400);
  const dx::Diagnosis d = diagnose(start, {history_measurement(truth, drive, 10)});
  require_effect(d, dx::Effect::amplitude_dependence);
  require_noise_floor(d);
}

TEST_CASE("diagnose, sine history: a missing Maxwell element is rate-dependence") {
  const std::string truth = "model truth { spring s (k = 300 N/mm)  friction f (k = 200 N/mm, uy = 50 um)  maxwell m (k = 200 N/mm, tau = 0.2 s) }";
  const std::string start =
      "model start {\n  spring s (k = 300 N/mm in [10, 10000])\n  friction f (k = 100 N/mm in [1, 10000], uy = 20 um in [0.1, 10000])\n}\n";
  const runtime::Drive drive = runtime::quasistatic_sine({1.0, 0.5}, 1.0, 3, 400);
  const dx::Diagnosis d = diagnose(start, {history_measurement(truth, drive, 11)});
  require_effect(d, dx::Effect::rate_dependence);
  require_noise_floor(d);
}

TEST_CASE("diagnose, sine histories: a slider-capped Maxwell branch is coupled-amplitude-frequency") {
  // Sines at 1 and 10 Hz, each at 1 mm and 0.1 mm: below its 30 N cap the branch is a Maxwell
  // element (tau = 10 ms), above it a friction-like force that depends on the rate.
  const std::string truth = R"(model truth { spring s (k = 400 N/mm)  friction f (k = 200 N/mm, uy = 40 um)
                               series b { slider cap (fy = 30 N)  maxwell arm (k = 400 N/mm, tau = 10 ms) } })";
  const std::string start =
      "model start {\n  spring s (k = 300 N/mm in [10, 10000])\n  friction f (k = 100 N/mm in [1, 10000], uy = 20 um in [0.1, 10000])\n}\n";
  const dx::Diagnosis d = diagnose(start, {history_measurement(truth, runtime::quasistatic_sine({1.0, 0.1}, 1.0, 2, 200), 15),
                                           history_measurement(truth, runtime::quasistatic_sine({1.0, 0.1}, 10.0, 2, 200), 16)});
  require_effect(d, dx::Effect::coupled_amplitude_frequency);
  require_noise_floor(d);
}

TEST_CASE("diagnose, sine histories: a column resonating at 12 Hz is inertia") {
  const std::string truth = R"(model truth { spring s (k = 500 N/mm)  maxwell m (k = 200 N/mm, tau = 5 ms)
                               series c { spring k1 (k = 150 N/mm)  parallel y { inerter b (b = 25 kg)  dashpot d (c = 0.6 N*s/mm) } } })";
  const std::string start =
      "model start {\n  spring s (k = 400 N/mm in [10, 10000])\n  maxwell m (k = 100 N/mm in [1, 10000], tau = 10 ms in [0.01, 10000])\n}\n";
  std::vector<runtime::FitDataSet> data;
  unsigned seed = 17;
  for (double f : {5.0, 12.0, 25.0}) data.push_back(history_measurement(truth, runtime::quasistatic_sine({0.5}, f, 4, 200), seed++));
  const dx::Diagnosis d = diagnose(start, data);
  require_effect(d, dx::Effect::inertia);
  require_noise_floor(d);
}

TEST_CASE("diagnose, static loops the model already explains give none") {
  const std::string truth = "model truth { spring s (k = 250 N/mm)  friction f (k = 300 N/mm, uy = 80 um) }";
  const std::string start =
      "model start {\n  spring s (k = 300 N/mm in [10, 10000])\n  friction f (k = 100 N/mm in [1, 10000], uy = 20 um in [0.1, 10000])\n}\n";
  const runtime::Drive drive = runtime::static_triangle({3.0, 1.0, 0.3}, 0.05, 1, 400);
  require_none(diagnose(start, {history_measurement(truth, drive, 12)}));
}

}  // namespace diagnosis_hidden_effects_test
