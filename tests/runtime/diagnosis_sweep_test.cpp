// rheo diagnose over draws of a second, independent generator (diagnosis_generator.hpp: uneven
// and incomplete grids, force-amplitude or relative noise, no phase noise, heteroscedastic and
// heavy-tailed noise, repeated cycles): pure noise on a model that explains its data must give
// none, and a hidden effect must be named or at least not called none; the noise estimate must
// be near the noise the generator drew.
//
// The suite runs a few draws (fewer under AddressSanitizer); RHEO_DIAGNOSE_SWEEP=N runs N seeds
// of every case (from RHEO_DIAGNOSE_SWEEP_FIRST, default 1; RHEO_DIAGNOSE_SWEEP_ONLY=none for one
// case, RHEO_DIAGNOSE_SWEEP_KIND=harmonic or history for one kind of data) and prints one line per diagnosis and the rates (about a minute per seed);
// RHEO_DIAGNOSE_SWEEP_VERBOSE=1 adds every candidate under its diagnosis; RHEO_DIAGNOSE_SWEEP_DUMP=DIR
// writes each harmonic draw as a model and a table for the command line (dump below).
#include "runtime/diagnosis/diagnose.hpp"

#include "diagnosis_generator.hpp"
#include "diagnosis_support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>

namespace diagnosis_sweep_test {

using namespace rheo;
namespace dx = runtime::diagnosis;
namespace gen = test::generated;

namespace {

unsigned env_count(const char* name) {
  const char* value = std::getenv(name);
  return value ? static_cast<unsigned>(std::max(0, std::atoi(value))) : 0u;
}

// The effect the generator hid, as diagnose names it.
dx::Effect expected(gen::Hidden h) {
  switch (h) {
    case gen::Hidden::none: return dx::Effect::none;
    case gen::Hidden::friction: return dx::Effect::amplitude_dependence;
    case gen::Hidden::maxwell: return dx::Effect::rate_dependence;
    case gen::Hidden::column: return dx::Effect::inertia;
    case gen::Hidden::play: return dx::Effect::backlash;
    case gen::Hidden::split_yield:
    case gen::Hidden::even_spring: return dx::Effect::asymmetry;
    case gen::Hidden::capped_maxwell: return dx::Effect::coupled_amplitude_frequency;
    case gen::Hidden::offset: return dx::Effect::offset;
  }
  return dx::Effect::none;
}

struct Outcome {
  std::string line;
  bool wrong = false;  // none on a hidden effect, or anything but none on pure noise
  bool named_right = false;
  double gap = 0.0;          // of the start model as fitted
  double noise_ratio = 0.0;  // estimated over true noise (the floor on grids, the force SD on histories)
};

// D, diagnosed on SC (HIDDEN hidden in it, drawn with SEED), as the sweep counts it.
Outcome outcome(const dx::Diagnosis& d, const gen::Scenario& sc, gen::Hidden hidden, unsigned seed) {
  Outcome o;
  const bool harmonic = sc.data.front().is_harmonic();
  o.noise_ratio = !d.noise.estimated ? 0.0 : harmonic ? d.noise.floor / sc.floor : d.noise.force / sc.force;
  o.named_right = d.verdict == dx::Verdict::named && d.effect == expected(hidden);
  o.gap = d.gap_before;
  o.wrong = hidden == gen::Hidden::none ? d.verdict != dx::Verdict::none : d.verdict == dx::Verdict::none;
  o.line = fmt::format(
      "{:5} {:14} {:28} gap {:.4g}->{:.4g} noise est/true {:.3f}{} chi2 ratio {:.3g}  [{}]", seed, gen::hidden_name(hidden), dx::verdict_name(d),
      d.gap_before, d.gap_after, o.noise_ratio,
      harmonic ? fmt::format(" (K {:.3f}, phase {:.3f})", d.noise.stiffness / sc.stiffness, sc.phase > 0.0 ? d.noise.phase / sc.phase : 0.0)
               : std::string(),
      d.chi_square_ratio, sc.description);
  if (std::getenv("RHEO_DIAGNOSE_SWEEP_VERBOSE")) o.line += "\n      truth: " + sc.truth;
  if (std::getenv("RHEO_DIAGNOSE_SWEEP_VERBOSE"))  // every candidate, screened and refitted
    for (const auto& c : d.candidates)
      o.line += fmt::format("\n      {:28} screened {:.3f}  {}  {}{}", dx::effect_name(c.screened.effect), c.screened.gain,
                            c.refitted ? fmt::format("gap {:.4g} BIC {:.1f} p {}", c.gap_after, c.criterion, c.parameters) : "not refitted",
                            dx::trial_summary(c.screened.trial), c.chosen ? "  <- chosen" : "") +
                (c.limit_of.empty() ? std::string() : "\n        " + c.limit_of) +
                (c.refitted && !c.fitted.empty() ? "\n        refitted: " + c.fitted : std::string());
  return o;
}

// With RHEO_DIAGNOSE_SWEEP_DUMP=DIR, a draw's start model and data are written to
// DIR/<hidden>_<seed>.rheo and .csv (a harmonic table; a history's files <hidden>_<seed>_<k>.csv
// with the word history in the stem, <hidden>_history_<seed>), for `rheo diagnose
// DIR/play_3.rheo` (the model's fit block names the data; the truth in its first line).
void dump(const gen::Scenario& sc, gen::Hidden hidden, unsigned seed) {
  const char* dir = std::getenv("RHEO_DIAGNOSE_SWEEP_DUMP");
  if (!dir) return;
  const bool harmonic = sc.data.front().is_harmonic();
  const std::string name = fmt::format("{}{}_{}", gen::hidden_name(hidden), harmonic ? "" : "_history", seed);
  std::string lines;
  for (std::size_t k = 0; k < sc.data.size(); ++k) {
    const std::string file = harmonic ? name + ".csv" : fmt::format("{}_{}.csv", name, k + 1);
    std::ofstream csv(fmt::format("{}/{}", dir, file));
    if (harmonic) {
      csv << "amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n";
      const auto& h = sc.data[k].harmonic();
      for (std::size_t i = 0; i < h.size(); ++i)
        csv << fmt::format("{:.17g},{:.17g},{:.17g},{:.17g}\n", h.amplitude[i], h.frequency[i], h.stiffness[i],
                           h.phase[i] * 180.0 / std::numbers::pi);
    } else {
      csv << "time [s],displacement [mm],force [N]\n";
      const auto& h = sc.data[k].history();
      for (std::size_t i = 0; i < h.force.size(); ++i)
        csv << fmt::format("{:.17g},{:.17g},{:.17g}\n", h.drive.time[i], h.drive.displacement[i], h.force[i]);
    }
    const auto& offset = sc.data[k].force_offset;
    const std::string declared = !offset.given ? ""
                                 : offset.free ? ", force_offset = free"
                                               : fmt::format(", force_offset = {:.17g} N", offset.value);
    lines += fmt::format("  data \"{}\"{}\n", file, declared);
  }
  std::ofstream model(fmt::format("{}/{}.rheo", dir, name));
  model << "# " << sc.truth << "\n" << sc.start << "fit start {\n" << lines << "}\n";
}

Outcome run(const gen::Scenario& sc, gen::Hidden hidden, unsigned seed) {
  dump(sc, hidden, seed);
  return outcome(test::diagnose(sc.start, sc.data), sc, hidden, seed);
}

// A diagnosis of SC, with its outcome as the sweep counts it.
struct Diagnosed {
  dx::Diagnosis d;
  Outcome o;
};
Diagnosed diagnosed(const gen::Scenario& sc, gen::Hidden hidden, unsigned seed) {
  Diagnosed out{test::diagnose(sc.start, sc.data), {}};
  out.o = outcome(out.d, sc, hidden, seed);
  return out;
}

// The candidate D added (CandidateOutcome::chosen), or null.
const dx::CandidateOutcome* chosen_candidate(const dx::Diagnosis& d) {
  const auto it = std::find_if(d.candidates.begin(), d.candidates.end(), [](const dx::CandidateOutcome& c) { return c.chosen; });
  return it == d.candidates.end() ? nullptr : &*it;
}

struct Tally {
  int runs = 0, wrong = 0, right = 0, invisible = 0;
  void add(const Outcome& o, bool visible) {
    ++runs, right += o.named_right;
    if (visible) wrong += o.wrong;
    else ++invisible;
  }
};

// Every case of SEEDS draws from FIRST, harmonic and history; prints a line per diagnosis and the
// rates. A hidden effect counts as a miss only where the data show it: the start model's gap at
// least 1.25 times the gap it leaves on the same grid and noise with nothing hidden (a Maxwell
// element of 5 ms under sines at 0.2 Hz, or friction against a Maxwell element under triangles
// at one rate, is not in the data).
std::map<std::string, Tally> sweep(unsigned first, unsigned seeds) {
  std::map<std::string, Tally> tally;
  const char* only = std::getenv("RHEO_DIAGNOSE_SWEEP_ONLY");        // one case by its hidden_name, e.g. "none"
  const char* kind = std::getenv("RHEO_DIAGNOSE_SWEEP_KIND");        // "harmonic" or "history": one kind of data only
  const char* rho = std::getenv("RHEO_DIAGNOSE_SWEEP_CORRELATION");  // the history noise's lag-1 autocorrelation
  const double correlation = rho ? std::atof(rho) : 0.0;
  const std::vector<gen::Hidden> on_grids{gen::Hidden::none, gen::Hidden::friction, gen::Hidden::maxwell, gen::Hidden::column, gen::Hidden::play};
  const std::vector<gen::Hidden> on_histories{gen::Hidden::none,        gen::Hidden::friction,    gen::Hidden::maxwell,        gen::Hidden::play,
                                              gen::Hidden::split_yield, gen::Hidden::even_spring, gen::Hidden::capped_maxwell, gen::Hidden::offset};
  for (unsigned seed = first; seed < first + seeds; ++seed)
    for (const bool history : {false, true}) {
      if (kind && std::string(kind) != (history ? "history" : "harmonic")) continue;
      double none_gap = 0.0;
      for (gen::Hidden h : history ? on_histories : on_grids) {
        if (only && std::string(only) != gen::hidden_name(h)) continue;
        const Outcome o = run(history ? gen::history_scenario(seed, h, correlation) : gen::harmonic_scenario(seed, h), h, seed);
        if (h == gen::Hidden::none) none_gap = o.gap;
        const bool visible = h == gen::Hidden::none || o.gap >= 1.25 * none_gap;
        std::cout << (history ? "history  " : "harmonic ") << o.line << (visible ? "" : "  (not in the data)") << std::endl;
        tally[fmt::format("{} {}", history ? "history" : "harmonic", gen::hidden_name(h))].add(o, visible);
      }
    }
  for (const auto& [name, t] : tally)
    std::cout << fmt::format("{:24} {} runs: {} wrong verdicts ({}), {} named right, {} not in the data\n", name, t.runs, t.wrong,
                             name.ends_with("none") ? "not none: false positives" : "none: misses", t.right, t.invisible);
  return tally;
}

}  // namespace

// Pure noise of fixed size in newtons on the force amplitude (relative stiffness noise up to 8
// times larger at the smallest amplitude than at the largest): weighed as noise of one size, the
// small amplitudes' noise looked like amplitude dependence (draw 5: a slider-capped Maxwell arm
// named, chi^2 / (N - p) = 1.49 with the stiffness noise estimated at 0.58 of its RMS); the noise
// profile (noise_profile.hpp) weighs each point by its own noise.
//
// Draw 6 has no phase noise: the noise estimated again on the residual of the least chi^2
// (criterion.hpp noise_at_likelihood_maximum) would follow the phases that fit weighs most and
// find a smaller phase noise still (chi^2 / (N - p) = 3.6, unexplained), and is not taken.
TEST_CASE("diagnose sweep: pure noise of fixed size on the force amplitude gives none, also without phase noise") {
  for (const unsigned seed : {5u, 6u}) {
    if (test::kUnderSanitizer && seed > 5u) break;
    const gen::Scenario sc = gen::harmonic_scenario(seed, gen::Hidden::none);
    const Outcome o = run(sc, gen::Hidden::none, seed);
    INFO(o.line);
    CHECK_FALSE(o.wrong);
  }
}

// A load cell's zero in every file, 2-10 % of max|F| of either sign (one file, then three, each
// its own): named offset, the gap to the noise, and each file's offset recovered.
TEST_CASE("diagnose sweep: a hidden force offset in one and in three history files is offset, each file's value recovered") {
  for (const unsigned seed : {3u, 4u}) {
    const gen::Scenario sc = gen::history_scenario(seed, gen::Hidden::offset);
    const dx::Diagnosis d = test::diagnose(sc.start, sc.data);
    const Outcome o = outcome(d, sc, gen::Hidden::offset, seed);
    INFO(o.line);
    CHECK(o.named_right);
    REQUIRE(d.after.has_value());
    CHECK(d.gap_after < 1.5 * sc.force);
    REQUIRE(d.freed_offsets.size() == sc.offsets.size());
    for (std::size_t k = 0; k < sc.offsets.size(); ++k) {
      const double scale = sc.data[k].history().force_scale;
      CHECK(std::abs(d.after->datasets[k].force_offset.value - sc.offsets[k]) < 0.005 * scale);
    }
  }
}

// Noise correlated from sample to sample (AR(1), lag-1 autocorrelation 0.8: a rig's
// anti-aliasing filter) on a model that explains the data: none. Before the noise was fitted over
// lags (noise_estimate.hpp) it was estimated at 0.38 of its size, and every draw was unexplained.
TEST_CASE("diagnose sweep: correlated pure noise in histories gives none, its size found") {
  for (const unsigned seed : {2u, 4u}) {
    const gen::Scenario sc = gen::history_scenario(seed, gen::Hidden::none, 0.8);
    const Outcome o = run(sc, gen::Hidden::none, seed);
    INFO(o.line);
    CHECK_FALSE(o.wrong);
    CHECK(o.noise_ratio == doctest::Approx(1.0).epsilon(0.1).scale(0.0));
  }
}

// Free play (0.61 mm wide, 0.078 mm off centre) engaging at the top amplitudes of an 8 x 7 grid:
// a yeoh spring with one parameter fewer fits within the parsimony margin of the backlash
// candidate's gap (0.0103 against 0.0096) with a chi^2 about twice its, a difference of more
// than 10 times the residual's overdispersion, so the data decide (criterion.hpp
// decisively_lower); the margin alone named nonlinear-elasticity.
TEST_CASE("diagnose sweep: free play at the top amplitudes of a grid is backlash where a yeoh spring fits within the margin but decisively worse") {
  const Diagnosed r = diagnosed(gen::harmonic_scenario(3, gen::Hidden::play), gen::Hidden::play, 3);
  INFO(r.o.line);
  CHECK(r.o.named_right);
  CHECK(r.d.reason.find("which the data decide") != std::string::npos);
}

TEST_CASE("diagnose sweep over a second generator (RHEO_DIAGNOSE_SWEEP seeds)") {
  const unsigned seeds = env_count("RHEO_DIAGNOSE_SWEEP");
  if (seeds == 0) return;
  const char* first = std::getenv("RHEO_DIAGNOSE_SWEEP_FIRST");
  sweep(first ? static_cast<unsigned>(std::max(1, std::atoi(first))) : 1u, seeds);
}

// The noise estimate on pure noise of diagnosis_support.hpp's grid (1 %, 0.15 deg): estimate
// over injected noise for seeds 100 to 100 + RHEO_NOISE_SWEEP - 1, the model's fit and noise
// alone (no candidate refitted).
TEST_CASE("diagnose noise estimate over pure-noise draws of the 6 x 6 grid (RHEO_NOISE_SWEEP seeds)") {
  const unsigned seeds = env_count("RHEO_NOISE_SWEEP");
  if (seeds == 0) return;
  const double s_k = 0.01, s_p = 0.15 * std::numbers::pi / 180.0;
  double sum_log = 0.0, sum_abs_log = 0.0, worst = 1.0;
  for (unsigned seed = 100; seed < 100 + seeds; ++seed) {
    const runtime::FitDataSet data = test::harmonic_measurement(test::kExplainedTruth, seed);
    double floor = 0.0;
    for (double phase : data.harmonic().phase) floor += s_k * s_k + std::pow(s_p / std::tan(phase), 2) + 0.5 * std::pow(s_p, 4);
    floor = std::sqrt(floor) / static_cast<double>(data.harmonic().size());
    const dx::Diagnosis d = test::diagnose(test::kExplainedStart, {data}, false, 0);
    const double ratio = d.noise.floor / floor;
    sum_log += std::log(ratio), sum_abs_log += std::abs(std::log(ratio));
    if (std::abs(std::log(ratio)) > std::abs(std::log(worst))) worst = ratio;
    std::cout << fmt::format("{:4} floor est/true {:.3f}  K {:.3f}  phase {:.3f}  chi2 ratio {:.3f}  verdict {}\n", seed, ratio,
                             d.noise.stiffness / s_k, d.noise.phase / s_p, d.chi_square_ratio, dx::verdict_name(d));
  }
  std::cout << fmt::format("floor est/true: geometric mean {:.3f}, mean |ln| {:.3f}, worst {:.3f}\n", std::exp(sum_log / seeds),
                           sum_abs_log / seeds, worst);
}

// A fluid column resonating at 9 Hz (107 N/mm onto 33 kg, damping ratio 0.18) between the
// grid's 2.8 and 11.9 Hz: the screen, with the model's other elements held, sizes its column at
// the top of the band (57 Hz), and the refit's global look sampled the column's mass a decade
// either side of that (with the screened chamber, resonances above 18 Hz); its local searches stayed there (err 0.0317,
// a resonance at the band's edge that cannot earn: unexplained). Masses and dampings are sampled
// over what resonates, and relaxes, within the measured band (global_look.hpp): err 0.00935, the
// true structure's own fit.
TEST_CASE("diagnose sweep: a column resonating inside the band far from where the screen sized it is inertia, at the true structure's gap") {
  const Diagnosed r = diagnosed(gen::harmonic_scenario(4, gen::Hidden::column), gen::Hidden::column, 4);
  INFO(r.o.line);
  CHECK(r.o.named_right);
  CHECK(r.d.gap_after < 0.0105);  // the truth's structure fitted from the truth: 0.00935
}

// Yield forces of 10.4 N in tension and 19.6 N in compression (one file of slow sines): past its
// first slip such a friction element is a symmetric one (15 N) under a constant force of
// -4.6 N, and only the first loading tells the two apart. The screen held the model still and
// ranked an added one-sided friction element (3 parameters) first, the model's own element made
// one-sided (1) within 0.2 % of it; refitted alone, the added element ended above the offset
// (p 6, named offset). Refitted beside it (screen.hpp ScreenedEffect::simpler), the split
// element reaches below the offset at the same p, its yield forces within 1 % of the truth's.
TEST_CASE("diagnose sweep: split yield forces in one sine file are asymmetry, the model's own friction element split") {
  const Diagnosed r = diagnosed(gen::history_scenario(3, gen::Hidden::split_yield), gen::Hidden::split_yield, 3);
  INFO(r.o.line);
  CHECK(r.o.named_right);
  REQUIRE(r.d.after.has_value());
  const dx::CandidateOutcome* split = chosen_candidate(r.d);
  REQUIRE(split != nullptr);
  CHECK(split->screened.trial.shape == dx::Shape::one_sided_element);
  CHECK(split->limit_of.find("parsimony margin") != std::string::npos);
  const runtime::Network& after = r.d.after->network;
  CHECK(after.parameter(test::parameter_index(after, "f.fy_pos")) == doctest::Approx(10.41).epsilon(0.01));
  CHECK(after.parameter(test::parameter_index(after, "f.fy_neg")) == doctest::Approx(19.59).epsilon(0.01));
}

// A friction element hidden in a grid whose smallest amplitudes have phases near the phase
// noise. Seed 3 (8 x 7, phases of 0.2-0.5 deg under 0.068 deg of noise): eq. 5.1's damping terms
// there pulled the friction element's refit to a chi^2 of 307 and a slider-capped Maxwell
// arm's (tau 17 s: friction with a trace of relaxation) to 120, and BICs compared at the refits
// named the coupling; at their likelihood's maximum their chi^2 are 100 and 99, one parameter
// apart. Seed 8 (5 x 5): at their maximum the capped arm's BIC is 1.2 below the friction
// element's, which is not positive evidence for its parameter (criterion.hpp positively_lower).
TEST_CASE("diagnose sweep: hidden friction is amplitude-dependence where eq. 5.1's refits leave their chi^2 far apart") {
  for (const unsigned seed : {3u, 8u}) {
    const Diagnosed r = diagnosed(gen::harmonic_scenario(seed, gen::Hidden::friction), gen::Hidden::friction, seed);
    INFO(r.o.line);
    CHECK(r.o.named_right);
    const dx::CandidateOutcome* chosen = chosen_candidate(r.d);
    REQUIRE(chosen != nullptr);
    CHECK(chosen->at_likelihood_maximum);
  }
}

// A slider-capped Maxwell arm (162 N; 868 N/mm, 179 ms) hidden beside a spring, a Maxwell
// element (7 ms) and a friction element, in three sine files: the model's fit took the arm into
// its own elements (the Maxwell element's tau 132 ms, the friction element's k 950 N/mm for
// 114), every refit from that fit stopped at 0.0303 against the noise's 0.0069, and the verdict
// was unexplained. Fitted as the model was, from the file's start values (diagnose.hpp step 4),
// the capped arm reaches the noise with the truth's values.
TEST_CASE("diagnose sweep: a capped Maxwell arm that the model's fit took into its own elements is found from the file's start values") {
  const Diagnosed r = diagnosed(gen::history_scenario(7, gen::Hidden::capped_maxwell), gen::Hidden::capped_maxwell, 7);
  INFO(r.o.line);
  CHECK(r.o.named_right);
  const dx::CandidateOutcome* chosen = chosen_candidate(r.d);
  REQUIRE(chosen != nullptr);
  CHECK(chosen->limit_of.find("file's start values") != std::string::npos);
  CHECK(r.d.gap_after < 1.0 * r.d.noise.floor);
  REQUIRE(r.d.after.has_value());
  const runtime::Network& after = r.d.after->network;
  const std::string arm = chosen->element;
  CHECK(after.parameter(test::parameter_index(after, arm + ".cap.fy")) == doctest::Approx(162.0).epsilon(0.02));
  CHECK(after.parameter(test::parameter_index(after, arm + ".arm.tau")) == doctest::Approx(0.1787).epsilon(0.02).scale(0.0));
}

// A friction element hidden beside a spring and a Maxwell element, in two files of slow
// triangles. Seed 6 (326.5 N/mm, 66.1 um): the screen ranked a friction element fourth (36.3 %
// against 36.4 % for a capped fluid column), and only the first three are refitted; the
// column's limit, a slider-capped Maxwell arm, refitted to tau = 2.4e5 s, a friction element
// with one parameter more, and was named coupled. Seed 12 (159.9 N/mm, 51.9 um): the arm
// refitted to tau = 8.4 s, within the files' cycles but long against their stick phases. The
// arm's limit tau -> infinity (candidate_model.hpp friction_limit) is refitted beside it and
// wins by parsimony, with the truth's values.
TEST_CASE("diagnose sweep: friction hidden in slow triangles is amplitude-dependence, the limit tau -> infinity of a refitted capped arm") {
  const struct {
    unsigned seed;
    double k, uy;  // the truth's [N/mm], [mm]
  } cases[] = {{6, 326.5, 0.06614}, {12, 159.9, 0.05185}};
  for (const auto& c : cases) {
    const Diagnosed r = diagnosed(gen::history_scenario(c.seed, gen::Hidden::friction), gen::Hidden::friction, c.seed);
    INFO(r.o.line);
    CHECK(r.o.named_right);
    const dx::CandidateOutcome* chosen = chosen_candidate(r.d);
    REQUIRE(chosen != nullptr);
    CHECK(chosen->screened.trial.shape == dx::Shape::friction);
    CHECK(chosen->limit_of.find("tau -> infinity") != std::string::npos);
    REQUIRE(r.d.after.has_value());
    const runtime::Network& after = r.d.after->network;
    CHECK(after.parameter(test::parameter_index(after, chosen->element + ".k")) == doctest::Approx(c.k).epsilon(0.03));
    CHECK(after.parameter(test::parameter_index(after, chosen->element + ".uy")) == doctest::Approx(c.uy).epsilon(0.03).scale(0.0));
  }
}

// A slider-capped Maxwell arm (161.9 N; 416.6 N/mm, 9.7 s) hidden beside a spring, a Maxwell and
// a friction element (326.5 N/mm, 66.1 um), under slow triangles: the refits ended with the two
// in each other's roles (the arm at 30 N, the friction element carrying the cap), and its limit,
// a friction element, was named. Searched again with their stiffnesses and yield forces
// exchanged (candidate_model.hpp roles_exchanged), the arm takes the truth's values.
TEST_CASE("diagnose sweep: a slow capped arm whose refit took the friction element's role is found with the roles exchanged") {
  const Diagnosed r = diagnosed(gen::history_scenario(6, gen::Hidden::capped_maxwell), gen::Hidden::capped_maxwell, 6);
  INFO(r.o.line);
  CHECK(r.o.named_right);
  const dx::CandidateOutcome* chosen = chosen_candidate(r.d);
  REQUIRE(chosen != nullptr);
  REQUIRE(chosen->screened.trial.shape == dx::Shape::capped_maxwell);
  REQUIRE(r.d.after.has_value());
  const runtime::Network& after = r.d.after->network;
  CHECK(after.parameter(test::parameter_index(after, chosen->element + ".cap.fy")) == doctest::Approx(161.9).epsilon(0.03));
  CHECK(after.parameter(test::parameter_index(after, chosen->element + ".arm.k")) == doctest::Approx(416.6).epsilon(0.03));
  CHECK(after.parameter(test::parameter_index(after, "f.k")) == doctest::Approx(326.5).epsilon(0.03));
}

}  // namespace diagnosis_sweep_test
