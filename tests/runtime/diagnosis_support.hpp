// Measurements with a known truth for the diagnose tests: data simulated from a model given as
// text, with the noise of examples/data (stiffness x (1 + 0.01 N(0,1)), phase + 0.15 deg
// N(0,1); histories: force + 0.003 max|F| N(0,1)), and diagnose() with the tests' settings:
// harmonic tables by the default solver, as rheo diagnose runs them (closed forms and
// event-driven periodic states; fixed steps until 2026-11-29, 5-10x the time), histories by
// fixed steps.
#pragma once

#include "runtime/diagnosis/diagnose.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/protocols/run_history.hpp"
#include "portable_random.hpp"
#include "support.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace rheo::test {

inline const std::vector<double> kAmplitudes{0.05, 0.1, 0.2, 0.5, 1.0, 2.0};  // mm
inline const std::vector<double> kFrequencies{1, 2, 5, 10, 20, 40};           // Hz

inline rheo::runtime::HarmonicOptions simulation_options() {
  rheo::runtime::HarmonicOptions o;
  o.steps_per_cycle = 256;
  o.solver = rheo::runtime::SolverChoice::fixed;
  o.threads = 2;
  return o;
}

// A model that explains harmonic_measurement's grid of kExplainedTruth: the verdict must be none.
inline const char* const kExplainedTruth =
    "model truth { spring s (k = 700 N/mm)  maxwell m (k = 90 N/mm, tau = 6 ms)  friction f (k = 250 N/mm, uy = 60 um) }";
inline const char* const kExplainedStart = R"(model start {
  spring s (k = 500 N/mm in [10, 10000])
  maxwell m (k = 100 N/mm in [1, 10000], tau = 10 ms in [0.01, 10000])
  friction f (k = 100 N/mm in [1, 10000], uy = 20 um in [0.1, 10000])
}
)";

inline rheo::runtime::FitDataSet harmonic_measurement(const std::string& truth, unsigned seed, const std::vector<double>& amplitudes = kAmplitudes) {
  const rheo::runtime::Network network = network_from(truth, "truth");
  const auto points = rheo::runtime::simulate_harmonic_grid(network, amplitudes, kFrequencies, simulation_options());
  test::PortableRandom random(seed);
  rheo::runtime::HarmonicData d;
  d.path = "hidden.csv";
  for (const auto& p : points) {
    d.amplitude.push_back(p.amplitude);
    d.frequency.push_back(p.frequency);
    d.stiffness.push_back(p.measures.stiffness * (1.0 + 0.01 * random.normal()));
    d.phase.push_back(p.measures.phase + 0.15 * std::numbers::pi / 180.0 * random.normal());
    d.rows.push_back(static_cast<int>(d.rows.size()) + 2);
  }
  return {d.path, 1.0, d};
}

inline rheo::runtime::FitDataSet history_measurement(const std::string& truth, const rheo::runtime::Drive& drive, unsigned seed) {
  const rheo::runtime::Network network = network_from(truth, "truth");
  const rheo::runtime::History h = rheo::runtime::run_history(network, drive, false, rheo::runtime::SolverChoice::fixed);
  double scale = 0.0;
  for (double f : h.force) scale = std::max(scale, std::abs(f));
  test::PortableRandom random(seed);
  rheo::runtime::HistoryData d;
  d.path = "hidden_history.csv";
  d.drive = drive;
  for (double f : h.force) d.force.push_back(f + 0.003 * scale * random.normal()), d.rows.push_back(static_cast<int>(d.rows.size()) + 2);
  d.force_scale = 0.0;
  for (double f : d.force) d.force_scale = std::max(d.force_scale, std::abs(f));
  return {d.path, 1.0, d};
}

// CONFIRM: the candidates refitted (0: the model's fit, noise and verdict alone).
inline rheo::runtime::diagnosis::Diagnosis diagnose(const std::string& start, const std::vector<rheo::runtime::FitDataSet>& data,
                                                    bool standard_errors = false, int confirm = 3) {
  rheo::runtime::diagnosis::DiagnoseSettings s;
  s.standard_errors = standard_errors;
  s.confirm = confirm;
  s.fit.score.harmonic = simulation_options();
  s.fit.score.harmonic.steps_per_cycle = 128;
  s.fit.score.harmonic.tolerance = 1e-6;
  // As rheo diagnose runs: the default solver, which diagnose() turns to fixed steps where
  // histories are fitted (diagnosis_solver).
  s.fit.score.harmonic.solver = rheo::runtime::SolverChoice::automatic;
  return rheo::runtime::diagnosis::diagnose({"start.rheo", start, "start"}, data, s);
}

}  // namespace rheo::test
