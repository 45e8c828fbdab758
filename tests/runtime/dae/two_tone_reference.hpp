// The differential test's two-tone drive and the fixed-step reference the IDA tests hold a
// history on it to; the fixed-step reference of a harmonic point; and a network both hold to it.
#pragma once

#include "runtime/core/drive.hpp"
#include "runtime/network/network.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/protocols/run_history.hpp"
#include "support.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace rheo::test {

// Differential seed 37, model 85: sharp bouc_wen elements (n up to 3.8, yielding at 13 um) in series
// blocks beside inerters, five blocks deep (dae_bouc_wen_test, solver_choice_test).
inline constexpr const char* kSeed37Model85 = R"(model m {
series {
spring (k = 43381.5 N/mm)
parallel {
bouc_wen (k = 12.5907 N/mm, n = 1.02764, fy = 3.57376 N)
series {
yeoh (D10 = 229.576 N/mm, D20 = -24.0131 N/mm^3, D30 = 15.3292 N/mm^5)
series { spring (k = 40.0703 N/mm) parallel { inerter (b = 0.0122674 kg) dashpot (c = 2.89935 N*s/mm) } }
}
series {
bouc_wen (k = 51.0288 N/mm, n = 3.76472, fy = 0.675519 N)
parallel {
bouc_wen (k = 372.424 N/mm, n = 2.2137, uy = 35.0081 um)
series {
spring (k = 140.772 N/mm)
yeoh (D10 = 57.8861 N/mm, D20 = -12.2415 N/mm^3, D30 = 2.41895 N/mm^5)
}
}
bouc_wen (k = 157.453 N/mm, n = 3.17353, fy = 0.554047 N)
}
}
series { spring (k = 110.458 N/mm) parallel { inerter (b = 0.0254594 kg) dashpot (c = 0.113719 N*s/mm) } }
}
quadratic_dashpot (cq = 0.0162639 N*s^2/mm^2)
})";

// From rest, 100 samples 1 ms apart of u(t) = 0.3 sin(2 pi 10 t) + 0.05 sin(2 pi 37 t) [mm]
// (30 mm/s at once), each interval cut into `steps` equal ones: the same piecewise-linear drive.
inline runtime::Drive two_tone_drive(int steps) {
  runtime::Drive d{{0.0}, {0.0}};
  const auto u = [](double t) { return 0.3 * std::sin(2 * std::numbers::pi * 10 * t) + 0.05 * std::sin(2 * std::numbers::pi * 37 * t); };
  for (int k = 1; k <= 100; ++k)
    for (int i = 1; i <= steps; ++i) {
      const double previous = u(1e-3 * (k - 1)), next = u(1e-3 * k);
      d.time.push_back(1e-3 * (k - 1) + 1e-3 * i / steps);
      d.displacement.push_back(previous + (next - previous) * i / steps);
    }
  return d;
}

// max_j |F_j - F*_j| / max_j |F_j| over the samples of two_tone_drive(1), where F holds the
// forces at those samples and F* = 2 F(128) - F(64) extrapolates fixed steps at 128 and 64
// steps per sample (their error is first order in the step where a quadratic dashpot's rate
// is held constant over a step).
inline double gap_to_extrapolated_fixed_steps(const runtime::Network& network, const std::vector<double>& force) {
  const auto coarse = runtime::run_history(network, two_tone_drive(64), false, runtime::SolverChoice::fixed);
  const auto fine = runtime::run_history(network, two_tone_drive(128), false, runtime::SolverChoice::fixed);
  double scale = 0.0, worst = 0.0;
  for (std::size_t j = 0; j < force.size(); ++j) {
    scale = std::max(scale, std::abs(force[j]));
    worst = std::max(worst, std::abs(force[j] - (2.0 * fine.force[128 * j] - coarse.force[64 * j])));
  }
  return worst / scale;
}

// How far IDA's harmonic point IDA lies from NETWORK's on fixed steps at 2048 and 4096 steps a
// cycle, extrapolated (2 X(4096) - X(2048)), at the same amplitude and frequency and with OPTIONS'
// other settings: the stiffness relative, the damping d absolute.
struct HarmonicGap {
  double stiffness = 0.0, damping = 0.0;
};
inline HarmonicGap gap_to_extrapolated_fixed_point(const runtime::Network& network, const runtime::HarmonicPoint& ida,
                                                   runtime::HarmonicOptions options) {
  options.solver = runtime::SolverChoice::fixed;
  options.steps_per_cycle = 2048;
  const auto coarse = runtime::simulate_harmonic_point(network, ida.amplitude, ida.frequency, options);
  options.steps_per_cycle = 4096;
  const auto fine = runtime::simulate_harmonic_point(network, ida.amplitude, ida.frequency, options);
  return {relative_error(ida.measures.stiffness, 2.0 * fine.measures.stiffness - coarse.measures.stiffness),
          std::abs(ida.measures.damping - (2.0 * fine.measures.damping - coarse.measures.damping))};
}

// IDA's harmonic point of NETWORK at AMPLITUDE [mm] and FREQUENCY [Hz] (time stepping, 256
// samples a cycle) and its gap to extrapolated fixed steps (gap_to_extrapolated_fixed_point; not
// meaningful where ida.converged is false).
struct IdaPointAgainstFixed {
  runtime::HarmonicPoint ida;
  HarmonicGap gap;
};
inline IdaPointAgainstFixed ida_point_against_fixed_steps(const runtime::Network& network, double amplitude, double frequency) {
  runtime::HarmonicOptions options;
  options.steady_state = runtime::SteadyState::time_stepping;
  options.steps_per_cycle = 256;
  options.solver = runtime::SolverChoice::sundials;
  IdaPointAgainstFixed out{runtime::simulate_harmonic_point(network, amplitude, frequency, options), {}};
  if (out.ida.converged) out.gap = gap_to_extrapolated_fixed_point(network, out.ida, options);
  return out;
}

}  // namespace rheo::test
