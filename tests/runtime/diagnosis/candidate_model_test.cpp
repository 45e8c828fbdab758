// Candidates as models (candidate_model.hpp): a refitted gap written as a file can state it; a
// fluid column and its limit without inertia, each started from the other; a column with its
// walls' spring, started from the column.
#include "runtime/diagnosis/candidate_model.hpp"

#include "runtime/diagnosis/screen.hpp"
#include "runtime/diagnosis/trial.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/protocols/run_history.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <numbers>

namespace candidate_model_test {

using namespace rheo;

namespace {

struct ForceDifference {
  double largest = 0.0;     // max |F_a| [N]
  double difference = 0.0;  // max |F_a - F_b| [N]
};

// A and B driven by DRIVE on fixed steps: their forces compared sample by sample.
ForceDifference force_difference(const runtime::Network& a, const runtime::Network& b, const runtime::Drive& drive) {
  const auto fa = runtime::run_history(a, drive, false, runtime::SolverChoice::fixed).force;
  const auto fb = runtime::run_history(b, drive, false, runtime::SolverChoice::fixed).force;
  REQUIRE(fa.size() == fb.size());
  ForceDifference d;
  for (std::size_t k = 0; k < fa.size(); ++k)
    d.largest = std::max(d.largest, std::abs(fa[k])), d.difference = std::max(d.difference, std::abs(fa[k] - fb[k]));
  return d;
}

}  // namespace

TEST_CASE("a refitted gap centre beyond half the width is written at the edge of the play, with the same predictions") {
  const runtime::Network network = test::network_from(
      "model g { spring s (k = 10 N/mm)  series b { gap p (width = 2 mm in [0.1, 10], center = 0.5 mm in [-5, 5])  friction f (k = 300 N/mm, fy = 200 N) } }",
      "g");
  const int center = test::parameter_index(network, "b.p.center");
  std::vector<double> values = network.parameters();
  values[static_cast<std::size_t>(center)] = 1.7;  // where a fit may go: every solver then acts as if it were at +1 mm
  const runtime::Network beyond = network.with_parameters(values);
  const runtime::Network written = runtime::diagnosis::with_gaps_in_play(beyond);
  CHECK(written.parameter(center) == 1.0);
  CHECK(runtime::diagnosis::with_gaps_in_play(network).parameter(center) == 0.5);  // within the play: kept
  const ForceDifference d = force_difference(beyond, written, runtime::quasistatic_sine({3.0, 1.5}, 1.0, 2, 200));
  CHECK(d.largest > 100.0);
  CHECK(d.difference <= 1e-9 * d.largest);
  // An edge outside the bounds the centre was fitted in: it stays where it is.
  const runtime::Network bounded = test::network_from(
      "model g { series b { gap p (width = 2 mm in [0.1, 10], center = 0.5 mm in [0.2, 5])  spring k (k = 300 N/mm) } }", "g");
  std::vector<double> negative = bounded.parameters();
  negative[static_cast<std::size_t>(test::parameter_index(bounded, "b.p.width"))] = 0.2;
  CHECK(runtime::diagnosis::with_gaps_in_play(bounded.with_parameters(negative)).parameter(test::parameter_index(bounded, "b.p.center")) == 0.5);
}

TEST_CASE("a capped Maxwell element's optimum restarts the fluid column it is the limit of, and that column's limit is it again") {
  const runtime::Network limit = test::network_from(
      "model m { spring s (k = 100 N/mm)  series c { slider cap (fy = 30 N in [0.1, 1000])  maxwell arm (k = 250 N/mm in [1, 1e4], tau = 4 ms in [0.01, 1000]) } }",
      "m");
  runtime::diagnosis::Trial column;
  column.shape = runtime::diagnosis::Shape::capped_column, column.frequency = 20.0, column.damping_ratio = 0.3;
  const auto restart = runtime::diagnosis::column_from_limit(column, limit.model(), limit, "c");
  CHECK(restart.shape == runtime::diagnosis::Shape::capped_column);
  CHECK(restart.stiffness == doctest::Approx(250.0).epsilon(1e-14));
  CHECK(restart.slip * restart.stiffness == doctest::Approx(30.0).epsilon(1e-14));
  CHECK(restart.frequency == 20.0);
  CHECK(restart.damping_ratio == doctest::Approx(std::numbers::pi * 20.0 * 4e-3).epsilon(1e-14).scale(0.0));  // zeta = pi f_r tau
  // Written as a model, its chamber and channel are the arm's k and c = k tau, and its limit is the arm.
  std::string text = "model m { spring s (k = 100 N/mm)\n";
  for (const std::string& line : runtime::diagnosis::trial_statement(restart, "c", {250.0, 1.0})) text += line + "\n";
  const runtime::Network columned = test::network_from(text + "}", "m");
  CHECK(columned.parameter(test::parameter_index(columned, "c.column.channel.c")) == doctest::Approx(250.0 * 4e-3).epsilon(1e-9));
  const double b = columned.parameter(test::parameter_index(columned, "c.column.mass.b"));
  CHECK(std::sqrt(250.0 / b) / (2.0 * std::numbers::pi) == doctest::Approx(20.0).epsilon(1e-5));  // b written to 6 digits
  const auto back = runtime::diagnosis::resonance_free_limit(restart, columned.model(), columned, "c");
  CHECK(back.shape == runtime::diagnosis::Shape::capped_maxwell);
  CHECK(back.stiffness == doctest::Approx(250.0).epsilon(1e-9));
  CHECK(back.time == doctest::Approx(4e-3).epsilon(1e-9).scale(0));
  CHECK(back.slip * back.stiffness == doctest::Approx(30.0).epsilon(1e-9));
}

TEST_CASE("a refitted fluid column restarts with its walls' spring: the column as refitted, k_b = kBulgeStart k, resonating at sqrt((k + k_b)/b)") {
  // The column as a refit leaves it (the cap too high to slip at these amplitudes).
  const runtime::Network column = test::network_from(
      "model m { spring s (k = 100 N/mm)  series c { slider cap (fy = 5000 N in [0.1, 1e5])  spring chamber (k = 400 N/mm in [1, 1e4])  "
      "parallel column { inerter mass (b = 25 kg in [0.1, 1000])  dashpot channel (c = 1.5 N*s/mm in [0.01, 100]) } } }",
      "m");
  runtime::diagnosis::Trial screened;
  screened.shape = runtime::diagnosis::Shape::capped_column, screened.frequency = 10.0, screened.damping_ratio = 0.5;
  const auto bulged = runtime::diagnosis::bulged_column(screened, column.model(), column, "c");
  const double k = 400.0, b = 25e-3, c = 1.5, k_b = runtime::diagnosis::kBulgeStart * k;  // N/mm, N s^2/mm, N s/mm
  CHECK(bulged.shape == runtime::diagnosis::Shape::capped_column);
  CHECK(bulged.stiffness == k);
  CHECK(bulged.bulge == k_b);
  CHECK(bulged.slip * bulged.stiffness == doctest::Approx(5000.0).epsilon(1e-14));
  CHECK(bulged.frequency == doctest::Approx(std::sqrt(k / b) / (2.0 * std::numbers::pi)).epsilon(1e-14));
  CHECK(bulged.damping_ratio == doctest::Approx(c / (2.0 * std::sqrt(k * b))).epsilon(1e-14));
  CHECK(runtime::diagnosis::added_parameter_count(bulged) == 5);
  // Written as a model: the column's values, the walls' spring beside its mass and channel, and
  // K* of the stuck column 1/(1/k + 1/(k_b + i w c - b w^2)) beside the spring.
  std::string text = "model m { spring s (k = 100 N/mm)\n";
  for (const std::string& line : runtime::diagnosis::trial_statement(bulged, "c", {400.0, 1.0})) text += line + "\n";
  const runtime::Network walled = test::network_from(text + "}", "m");
  CHECK(walled.parameter(test::parameter_index(walled, "c.column.bulge.k")) == doctest::Approx(k_b).epsilon(1e-9));
  CHECK(walled.parameter(test::parameter_index(walled, "c.column.mass.b")) == doctest::Approx(b).epsilon(1e-5));  // b written to 6 digits
  CHECK(walled.parameter(test::parameter_index(walled, "c.column.channel.c")) == doctest::Approx(c).epsilon(1e-9));
  runtime::HarmonicOptions options;
  options.definition = runtime::HarmonicDefinition::first_harmonic;
  const double resonance = std::sqrt((k + k_b) / b) / (2.0 * std::numbers::pi);
  for (double f : {0.5 * resonance, resonance, 2.0 * resonance}) {
    CAPTURE(f);
    const double w = 2.0 * std::numbers::pi * f;
    const std::complex<double> expected = 100.0 + 1.0 / (1.0 / k + 1.0 / std::complex<double>(k_b - b * w * w, w * c));
    const auto point = runtime::simulate_harmonic_point(walled, 0.1, f, options);
    CHECK(point.measures.storage == doctest::Approx(expected.real()).epsilon(1e-4));
    CHECK(point.measures.loss == doctest::Approx(expected.imag()).epsilon(1e-4));
  }
  // The resonance the data must place is the walled one: inside a band around it, outside a band
  // around the column's own sqrt(k/b) that excludes it.
  runtime::diagnosis::DataScales around_walled, around_column;
  around_walled.frequency_low = 0.5 * resonance, around_walled.frequency_high = 2.0 * resonance;
  around_column.frequency_low = 0.5 * bulged.frequency, around_column.frequency_high = 1.05 * bulged.frequency;
  CHECK(resonance > 1.05 * bulged.frequency);
  CHECK(runtime::diagnosis::resolved_resonance(bulged, walled.model(), walled, "c", around_walled).empty());
  CHECK(!runtime::diagnosis::resolved_resonance(bulged, walled.model(), walled, "c", around_column).empty());
}

// A slider (fy) in series with a Maxwell arm (k, tau) is, as tau -> infinity, a slider in series
// with a spring: a friction element of k and uy = fy/k (eq. 2.9). Under sines of 1 Hz for 4 s
// an arm of tau = 1e4 s relaxes by about 4e-4 of its force within the history, and the two give
// the same forces to that.
TEST_CASE("a capped Maxwell arm has a friction element as its limit tau -> infinity, with the arm's loop where tau is long") {
  const std::string body = "spring s (k = 100 N/mm)  ";
  const runtime::Network arm = test::network_from(
      "model m { " + body + "series a { slider cap (fy = 30 N in [0.1, 1e5])  maxwell arm (k = 250 N/mm in [1, 1e4], tau = 1e4 s in [1e-5, 1e7]) } }",
      "m");
  runtime::diagnosis::Trial screened;
  screened.effect = runtime::diagnosis::Effect::coupled_amplitude_frequency, screened.shape = runtime::diagnosis::Shape::capped_maxwell;
  const auto limit = runtime::diagnosis::friction_limit(screened, arm.model(), arm, "a");
  CHECK(limit.shape == runtime::diagnosis::Shape::friction);
  CHECK(limit.effect == runtime::diagnosis::Effect::amplitude_dependence);
  CHECK(limit.stiffness == 250.0);
  CHECK(limit.slip == doctest::Approx(0.12).epsilon(1e-14).scale(0.0));  // mm
  CHECK(runtime::diagnosis::added_parameter_count(limit) == runtime::diagnosis::added_parameter_count(screened) - 1);
  std::string text = "model m { " + body;
  for (const std::string& line : runtime::diagnosis::trial_statement(limit, "a", {250.0, 1.0})) text += line + "\n";
  const runtime::Network friction = test::network_from(text + "}", "m");
  const ForceDifference d = force_difference(arm, friction, runtime::quasistatic_sine({0.5, 0.2}, 1.0, 2, 400));
  CHECK(d.largest > 50.0);
  CHECK(d.difference <= 1e-3 * d.largest);
  // The arm outlasts its sticking under those sines (uy = 0.12 mm: stuck acos(1 - 2 uy/a)/(2 pi f),
  // 0.16 s at 0.5 mm and 0.28 s at 0.2 mm); an arm of 0.1 s does not.
  runtime::HistoryData h;
  h.drive = runtime::quasistatic_sine({0.5, 0.2}, 1.0, 2, 400);
  const std::vector<runtime::FitDataSet> sines{runtime::FitDataSet{"sines", 1.0, h, {}, {}}};
  CHECK(runtime::diagnosis::outlasts_sticking(arm.model(), arm, "a", sines));
  std::vector<double> quick = arm.parameters();
  quick[static_cast<std::size_t>(test::parameter_index(arm, "a.arm.tau"))] = 0.1;
  CHECK_FALSE(runtime::diagnosis::outlasts_sticking(arm.model(), arm.with_parameters(quick), "a", sines));
}

// The longest a friction element of slip uy sticks: from a turning point until the drive has
// moved 2 uy. A sine point of amplitude a at f: acos(1 - 2 uy/a)/(2 pi f); a point of a <= uy
// never slips. A triangle at v: 2 uy/v.
TEST_CASE("the longest a friction element sticks under the drives: a sine's acos(1 - 2 uy/a)/(2 pi f), a triangle's 2 uy/v") {
  runtime::HarmonicData grid;
  grid.amplitude = {1.0, 0.5, 0.05}, grid.frequency = {1.0, 10.0, 0.01};  // the last never slips at uy = 0.1 mm
  const std::vector<runtime::FitDataSet> harmonic{runtime::FitDataSet{"grid", 1.0, grid, {}, {}}};
  CHECK(runtime::diagnosis::longest_stick(harmonic, 0.1) == doctest::Approx(std::acos(0.8) / (2.0 * std::numbers::pi)).epsilon(1e-12).scale(0.0));
  CHECK(runtime::diagnosis::longest_stick(harmonic, 2.0) == 0.0);
  runtime::HistoryData h;
  h.drive = runtime::static_triangle({1.0}, 0.5, 2, 400);  // 0.01 mm and 0.02 s a sample
  const std::vector<runtime::FitDataSet> history{runtime::FitDataSet{"triangle", 1.0, h, {}, {}}};
  CHECK(runtime::diagnosis::longest_stick(history, 0.1) == doctest::Approx(0.4).epsilon(1e-9).scale(0.0));
  CHECK(runtime::diagnosis::longest_stick(history, 0.33) == doctest::Approx(1.32).epsilon(1e-9));  // between samples
  CHECK(runtime::diagnosis::longest_stick(history, 1.1) == 0.0);  // 2.2 mm from a turning point at +-1 mm: never before the next
}

// A friction element and a capped Maxwell arm in each other's roles, exchanged: the arm takes the
// friction element's stiffness and yield force, the friction element the arm's (its slip uy =
// fy/k where it is given so), the arm's tau kept; a friction element with one-sided yield, or a
// value held, has no exchange.
TEST_CASE("a capped Maxwell arm and a root friction element exchange their stiffnesses and yield forces") {
  const runtime::Network network = test::network_from(
      "model m { spring s (k = 400 N/mm in [1, 1e4])  friction f (k = 634 N/mm in [1, 1e4], uy = 0.356 mm in [1e-4, 10])  "
      "series a { slider cap (fy = 20 N in [0.1, 1e5])  maxwell arm (k = 267 N/mm in [1, 1e4], tau = 0.86 s in [1e-5, 1e7]) } }",
      "m");
  const lang::CheckedModel& model = network.model();
  const auto exchanged = runtime::diagnosis::roles_exchanged(model, network, "a", model.root.children[1]);
  REQUIRE(exchanged.has_value());
  const runtime::Network swapped = network.with_parameters(*exchanged);
  CHECK(swapped.parameter(test::parameter_index(swapped, "a.arm.k")) == doctest::Approx(634.0).epsilon(1e-12));
  CHECK(swapped.parameter(test::parameter_index(swapped, "a.cap.fy")) == doctest::Approx(634.0 * 0.356).epsilon(1e-12));
  CHECK(swapped.parameter(test::parameter_index(swapped, "f.k")) == doctest::Approx(267.0).epsilon(1e-12));
  CHECK(swapped.parameter(test::parameter_index(swapped, "f.uy")) == doctest::Approx(20.0 / 267.0).epsilon(1e-12).scale(0.0));
  CHECK(swapped.parameter(test::parameter_index(swapped, "a.arm.tau")) == doctest::Approx(0.86).epsilon(1e-12).scale(0.0));
  CHECK(swapped.parameter(test::parameter_index(swapped, "s.k")) == 400.0);
  CHECK_FALSE(runtime::diagnosis::roles_exchanged(model, network, "a", model.root.children[0]).has_value());  // a spring
  const runtime::Network one_sided = test::network_from(
      "model m { friction f (k = 634 N/mm in [1, 1e4], fy_pos = 200 N in [1, 1e4], fy_neg = 250 N in [1, 1e4])  "
      "series a { slider cap (fy = 20 N in [0.1, 1e5])  maxwell arm (k = 267 N/mm in [1, 1e4], tau = 0.86 s in [1e-5, 1e7]) } }",
      "m");
  CHECK_FALSE(runtime::diagnosis::roles_exchanged(one_sided.model(), one_sided, "a", one_sided.model().root.children[0]).has_value());
  const runtime::Network held = test::network_from(
      "model m { friction f (k = 634 N/mm, uy = 0.356 mm in [1e-4, 10])  "
      "series a { slider cap (fy = 20 N in [0.1, 1e5])  maxwell arm (k = 267 N/mm in [1, 1e4], tau = 0.86 s in [1e-5, 1e7]) } }",
      "m");
  CHECK_FALSE(runtime::diagnosis::roles_exchanged(held.model(), held, "a", held.model().root.children[0]).has_value());
}

}  // namespace candidate_model_test
