// The typed settings of each protocol: defaults for what a block leaves out, values in internal
// units, the vocabularies' words, and command-line overrides.
#include "lang/frontend.hpp"
#include "lang/protocol_schema.hpp"
#include "lang/protocol_settings.hpp"

#include <doctest/doctest.h>

#include <variant>

namespace protocol_settings_test {

using namespace rheo::lang;

namespace {

const Protocol& only_protocol(const Program& program) {
  REQUIRE(program.simulations.size() == 1);
  REQUIRE(program.simulations[0].protocols.size() == 1);
  return program.simulations[0].protocols[0];
}

Program with_protocol(const std::string& line) {
  return compile_source("p.rheo", "model m { spring k (k = 1 N/mm) }\nsimulate {\n  " + line + "\n}\n");
}

// The settings of the one protocol LINE, as the alternative S (a copy: the program is gone).
template <class S>
S settings_of(const std::string& line) {
  return std::get<S>(only_protocol(with_protocol(line)).settings);
}

}  // namespace

TEST_CASE("words of every vocabulary round-trip and unknown words are refused") {
  for (const auto& w : harmonic_definition_words()) CHECK(word_of(*harmonic_definition_named(w)) == w);
  for (const auto& w : steady_state_words()) CHECK(word_of(*steady_state_named(w)) == w);
  for (const auto& w : solver_choice_words()) CHECK(word_of(*solver_choice_named(w)) == w);
  for (const auto& w : output_format_words()) CHECK(word_of(*output_format_named(w)) == w);
  CHECK(solver_choice_words() == std::vector<std::string>{"auto", "fixed", "sundials"});
  CHECK_FALSE(solver_choice_named("cvode").has_value());
  CHECK_FALSE(harmonic_definition_named("Thesis").has_value());
}

TEST_CASE("harmonic: the settings given in internal units, the defaults for the rest") {
  const Program program = with_protocol("harmonic frequency = 1 Hz .. 5 Hz step 2 Hz, amplitude = [200 um, 1 mm]");
  const auto& h = std::get<HarmonicSettings>(only_protocol(program).settings);
  CHECK(h.frequencies == std::vector<double>{1.0, 3.0, 5.0});
  CHECK(h.amplitudes == std::vector<double>{0.2, 1.0});
  CHECK(h.definition == HarmonicDefinition::thesis);
  CHECK(h.steady_state == SteadyState::automatic);
  CHECK(h.steps_per_cycle == 2048);
  CHECK(h.cycles_max == 400);
  CHECK(h.tolerance == 1e-9);
  CHECK(h.solver == SolverChoice::automatic);
  CHECK(h.format == OutputFormat::csv);
  CHECK_FALSE(h.elements);

  const Program given = with_protocol(
      "harmonic frequency = 2 Hz, amplitude = 1 mm, definition = first_harmonic, steady_state = time_stepping, "
      "steps_per_cycle = 64, cycles_max = 10, tolerance = 1e-6, solver = sundials, format = json, elements = all");
  const auto& g = std::get<HarmonicSettings>(only_protocol(given).settings);
  CHECK(g.definition == HarmonicDefinition::first_harmonic);
  CHECK(g.steady_state == SteadyState::time_stepping);
  CHECK(g.steps_per_cycle == 64);
  CHECK(g.cycles_max == 10);
  CHECK(g.tolerance == 1e-6);
  CHECK(g.solver == SolverChoice::sundials);
  CHECK(g.format == OutputFormat::json);
  CHECK(g.elements);
}

TEST_CASE("static, quasistatic, history and step decode to their own settings") {
  const auto s = settings_of<StaticSettings>("static velocity = 1 mm/s, amplitude = [1, 2] mm");
  CHECK(s.velocity == 1.0);
  CHECK(s.amplitudes == std::vector<double>{1.0, 2.0});
  CHECK(s.cycles == 2);
  CHECK_FALSE(s.dt.has_value());
  const auto timed = settings_of<StaticSettings>("static velocity = 1 mm/s, amplitude = 1 mm, dt = 5 ms");
  CHECK(timed.dt == doctest::Approx(0.005).scale(0.0));

  const auto q = settings_of<QuasistaticSettings>("quasistatic frequency = 0.1 Hz, amplitude = 1 mm, cycles = 3");
  CHECK(q.frequency == 0.1);
  CHECK(q.cycles == 3);
  CHECK(q.steps_per_cycle == 400);

  const auto h = settings_of<HistorySettings>("history file = \"road.csv\", substeps = 4");
  CHECK(h.file == "road.csv");
  CHECK(h.substeps == 4);
  CHECK(h.file_where.line == 3);
  CHECK(h.file_where.column > 1);

  // step: dt defaults to duration / 1000 and rise to dt.
  const auto st = settings_of<StepSettings>("step amplitude = -1 mm, duration = 2 s");
  CHECK(st.amplitude == -1.0);
  CHECK(st.dt == doctest::Approx(0.002).scale(0.0));
  CHECK(st.rise == doctest::Approx(0.002).scale(0.0));
  const auto ramp = settings_of<StepSettings>("step amplitude = 1 mm, duration = 2 s, dt = 10 ms, rise = 0.5 s");
  CHECK(ramp.dt == doctest::Approx(0.01).scale(0.0));
  CHECK(ramp.rise == doctest::Approx(0.5).scale(0.0));
}

TEST_CASE("an override replaces the written setting and the settings are decoded again") {
  Protocol p = only_protocol(with_protocol("step amplitude = 1 mm, duration = 2 s"));
  override_setting(p, parse_setting(ProtocolKind::step, "duration = 4 s"));
  const auto& st = std::get<StepSettings>(p.settings);
  CHECK(st.duration == 4.0);
  CHECK(st.dt == doctest::Approx(0.004).scale(0.0));  // the default follows the new duration
  override_setting(p, parse_setting(ProtocolKind::step, "dt = 1 ms"));
  CHECK(std::get<StepSettings>(p.settings).dt == doctest::Approx(0.001).scale(0.0));
  CHECK(std::get<StepSettings>(p.settings).rise == doctest::Approx(0.001).scale(0.0));
  CHECK(p.written.size() == 3);
}

}  // namespace protocol_settings_test
