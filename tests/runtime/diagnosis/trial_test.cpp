#include "runtime/diagnosis/trial.hpp"

#include "lang/frontend.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/network/network.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cmath>
#include <complex>
#include <numbers>

namespace trial_test {

using namespace rheo;
namespace dx = runtime::diagnosis;

namespace {

lang::Program compiled(const dx::Trial& trial) {
  std::string text = "model probe {\n";
  for (const auto& line : dx::trial_statement(trial, "added", {500.0, 2.0})) text += "  " + line + "\n";
  return lang::compile_source("probe.rheo", text + "}\n");
}

dx::Trial trial_of(dx::Shape shape) {
  dx::Trial t;
  t.shape = shape, t.stiffness = 200.0, t.time = 0.004, t.slip = 0.05, t.frequency = 20.0, t.damping_ratio = 0.3, t.bias = 0.4, t.k2 = 5.0;
  // The element a rebuilding shape writes (gapped_element: behind the play; one_sided_element:
  // split), its own parameters fixed so that the bounded ones are what the shape adds.
  static const std::string fixed_friction = "friction f (k = 300 N/mm, fy = 20 N)";
  static const std::string split_friction = "friction f (k = 300 N/mm, fy_pos = 28 N in [1, 200], fy_neg = 12 N in [1, 200])";
  if (shape == dx::Shape::gapped_element || shape == dx::Shape::one_sided_element) {
    t.replaces = fixed_friction.substr(9, 1);
    t.inner = shape == dx::Shape::gapped_element ? fixed_friction : split_friction;
    t.split_parameters = 2;
  }
  return t;
}

}  // namespace

TEST_CASE("diagnosis trial: every shape writes a statement that compiles, with bounds around its values") {
  for (dx::Shape shape : {dx::Shape::maxwell, dx::Shape::friction, dx::Shape::capped_maxwell, dx::Shape::capped_column, dx::Shape::tuned_column,
                          dx::Shape::mass, dx::Shape::yeoh, dx::Shape::asymmetric_friction, dx::Shape::even_spring, dx::Shape::gapped_spring,
                          dx::Shape::gapped_element, dx::Shape::one_sided_element}) {
    const dx::Trial trial = trial_of(shape);
    const lang::Program program = compiled(trial);
    const lang::CheckedModel& m = program.models.front();
    int bounded = 0;
    for (const auto& p : m.parameters)
      if (p.free) {
        ++bounded;
        CHECK(p.lower <= p.value);
        CHECK(p.value <= p.upper);
      }
    CHECK(bounded == dx::added_parameter_count(trial));  // an added yeoh: D10, D20, D30
    CHECK(!dx::trial_summary(trial).empty());
  }
  dx::Trial walled = trial_of(dx::Shape::capped_column);
  walled.bulge = 50.0;
  // The program held by name: a range-for over a member of a temporary reads freed memory.
  const lang::Program walled_program = compiled(walled);
  int bounded = 0;
  for (const auto& p : walled_program.models.front().parameters) bounded += p.free ? 1 : 0;
  CHECK(bounded == dx::added_parameter_count(walled));  // the column's four and the walls' k
  CHECK(bounded == 5);
  // Its resonance and damping ratio on the two springs the column's node rests on, k + k_b.
  const std::string summary = dx::trial_summary(walled);
  CHECK(summary.find(fmt::format("resonance {:.3g} Hz", 20.0 * std::sqrt(1.25))) != std::string::npos);
  CHECK(summary.find(fmt::format("damping ratio {:.2g}", 0.3 / std::sqrt(1.25))) != std::string::npos);
  CHECK(summary.find("walls (k = 50 N/mm)") != std::string::npos);
}

TEST_CASE("diagnosis trial: the tuned column resonates where its frequency says (closed form K*)") {
  // K* = 1/(1/k + 1/(i w c - b w^2)) with b = k/(2 pi f_r)^2: at f_r, b w^2 = k and
  // 1/K* = 1/k + 1/(i w c - k), which is infinite without damping (the resonance).
  const dx::Trial trial = trial_of(dx::Shape::tuned_column);
  const lang::Program program = compiled(trial);
  const runtime::Network network = runtime::Network::compile(program.models.front());
  runtime::HarmonicOptions o;
  o.definition = runtime::HarmonicDefinition::first_harmonic;
  const auto point = runtime::simulate_harmonic_point(network, 1.0, trial.frequency, o);
  const double w = 2.0 * std::numbers::pi * trial.frequency, b = trial.stiffness / (w * w);
  const double c = 2.0 * trial.damping_ratio * std::sqrt(trial.stiffness * b);
  const std::complex<double> expected = 1.0 / (1.0 / trial.stiffness + 1.0 / std::complex<double>(-trial.stiffness, w * c));
  CHECK(point.measures.stiffness == doctest::Approx(std::abs(expected)).epsilon(1e-4));
  CHECK(point.measures.phase == doctest::Approx(std::arg(expected)).epsilon(1e-4));
}

TEST_CASE("diagnosis trial: a yeoh replacing a spring keeps its linear stiffness, D10 = k / 2") {
  dx::Trial trial = trial_of(dx::Shape::yeoh);
  trial.replaces = "rubber";
  const auto lines = dx::trial_statement(trial, "rubber", {500.0, 2.0});
  REQUIRE(lines.size() == 1);
  CHECK(lines.front().starts_with("yeoh rubber (D10 = 100 N/mm"));
  CHECK(dx::added_parameter_count(trial) == 2);
}

TEST_CASE("diagnosis trial: the asymmetry and backlash shapes write the elements of their law") {
  const auto friction = dx::trial_statement(trial_of(dx::Shape::asymmetric_friction), "a", {500.0, 2.0});
  CHECK(friction.front().find("fy_pos = 14 N") != std::string::npos);  // k slip (1 + bias) = 200 0.05 1.4
  CHECK(friction.front().find("fy_neg = 6 N") != std::string::npos);
  dx::Trial even = trial_of(dx::Shape::even_spring);
  even.replaces = "rubber";
  const auto spring = dx::trial_statement(even, "rubber", {500.0, 2.0});
  CHECK(spring.front().starts_with("poly_spring rubber (k1 = 200 N/mm"));
  CHECK(spring.front().find("k2 = 5 N/mm^2") != std::string::npos);
  CHECK(dx::added_parameter_count(even) == 1);
  const auto play = dx::trial_statement(trial_of(dx::Shape::gapped_spring), "b", {500.0, 2.0});
  CHECK(play[1].find("width = 0.1 mm") != std::string::npos);    // 2 slip
  CHECK(play[1].find("center = 0.02 mm") != std::string::npos);  // bias slip
}

TEST_CASE("diagnosis trial: the mass is -k at its reference frequency (closed form K* = -b w^2)") {
  const dx::Trial trial = trial_of(dx::Shape::mass);
  const lang::Program program = compiled(trial);
  const runtime::Network network = runtime::Network::compile(program.models.front());
  runtime::HarmonicOptions o;
  o.definition = runtime::HarmonicDefinition::first_harmonic;
  for (double f : {trial.frequency, 3.0 * trial.frequency}) {
    const auto point = runtime::simulate_harmonic_point(network, 1.0, f, o);
    // b is written to 6 significant digits: 1e-5 relative.
    CHECK(point.measures.stiffness == doctest::Approx(trial.stiffness * (f / trial.frequency) * (f / trial.frequency)).epsilon(1e-5));
    CHECK(point.measures.phase == doctest::Approx(std::numbers::pi).epsilon(1e-9));
  }
}

}  // namespace trial_test
