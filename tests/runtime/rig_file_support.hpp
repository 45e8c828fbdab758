// The friction damper rig file of examples/data (friction_damper_rig.csv; its README says what it
// is): a displacement-controlled test programme run through a known model with rheo's fixed-step
// simulator, then written as a rig exports it, with a load-cell offset, a slow drift of the
// load cell's zero and seeded noise. Everything random comes from std::mt19937's 32-bit outputs
// mapped by the functions below (uniform: bits / 2^32; normal: Box-Muller), so that the file is
// the same wherever it is made (std::uniform_real_distribution and std::normal_distribution are
// not specified bit for bit).
#pragma once

#include "runtime/protocols/run_history.hpp"
#include "support.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace rheo::test::rig_file {

// The truth (N, mm, s): a weak elastic spring in parallel with a friction element whose yield
// differs in tension (13 kN) and compression (20 kN), engaged through free play of 6 mm whose
// centre lies 1.5 mm into tension (contact at +4.5 mm and -1.5 mm).
inline const char* kTruth = R"(model damper {
  spring s (k = 30 N/mm)
  series stop {
    gap      play (width = 6 mm, center = 1.5 mm)
    friction f    (k = 4000 N/mm, fy_pos = 13000 N, fy_neg = 20000 N)
  }
})";

inline constexpr double kSampleRate = 50.0;  // Hz
inline constexpr double kRest = 1.0;         // s at rest before the programme
inline constexpr double kOffset = -650.0;    // N, the load cell's reading at rest (t = 0)
inline constexpr double kDrift = 150.0;      // N, the zero's change over the whole record, linear in time
inline constexpr double kNoise = 60.0;       // N, standard deviation of the force noise
inline constexpr std::uint32_t kSeed = 20261125;

struct Sine {
  double amplitude;  // mm
  double frequency;  // Hz
  int cycles;
};
// Sines u = A sin(2 pi f t), each from 0 for whole cycles, in this order.
inline const std::vector<Sine> kSines{{12.0, 0.25, 2}, {25.0, 0.5, 2}, {38.0, 1.0, 2}, {20.0, 2.0, 3}};

// The earthquake-like segment: kQuakeLines sines with frequencies uniform in [0.2, 2.5] Hz,
// displacement amplitude proportional to 1/f and uniform phase, under the envelope
// (t/2)^2 for t < 2 s, 1 to 5 s, exp(-(t - 5)/2) after, times a half-cosine taper over the last
// 2 s so that it ends at rest; scaled to a peak of kQuakePeak.
inline constexpr double kQuakeDuration = 12.0;  // s
inline constexpr double kQuakePeak = 30.0;      // mm
inline constexpr int kQuakeLines = 40;

// Uniform in [0, 1) from one output of the generator.
inline double uniform(std::mt19937& bits) { return static_cast<double>(bits()) / 4294967296.0; }

// Standard normal by Box-Muller from two outputs (u1 in (0, 1], so the logarithm is finite).
inline double normal(std::mt19937& bits) {
  const double u1 = (static_cast<double>(bits()) + 1.0) / 4294967296.0;
  const double u2 = uniform(bits);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

// The displacement programme at kSampleRate, rounded to 1 um as the file writes it.
inline runtime::Drive programme(std::mt19937& bits) {
  std::vector<double> u(static_cast<std::size_t>(kRest * kSampleRate), 0.0);
  for (const Sine& s : kSines) {
    const int n = static_cast<int>(std::lround(s.cycles * kSampleRate / s.frequency));
    for (int k = 1; k <= n; ++k) u.push_back(s.amplitude * std::sin(2.0 * std::numbers::pi * s.frequency * k / kSampleRate));
  }
  constexpr auto lines = static_cast<std::size_t>(kQuakeLines);
  std::vector<double> frequency(lines), weight(lines), phase(lines);
  for (std::size_t i = 0; i < lines; ++i) {
    frequency[i] = 0.2 + 2.3 * uniform(bits);
    weight[i] = 1.0 / frequency[i];
    phase[i] = 2.0 * std::numbers::pi * uniform(bits);
  }
  const auto n = static_cast<std::size_t>(std::lround(kQuakeDuration * kSampleRate));
  std::vector<double> quake(n + 1, 0.0);
  double peak = 0.0;
  for (std::size_t k = 0; k <= n; ++k) {
    const double t = static_cast<double>(k) / kSampleRate;
    const double envelope = (t < 2.0   ? (t / 2.0) * (t / 2.0)
                             : t < 5.0 ? 1.0
                                       : std::exp(-(t - 5.0) / 2.0)) *
                            (t > kQuakeDuration - 2.0 ? 0.5 * (1.0 + std::cos(std::numbers::pi * (t - kQuakeDuration + 2.0) / 2.0)) : 1.0);
    double sum = 0.0;
    for (std::size_t i = 0; i < lines; ++i)
      sum += weight[i] * (std::sin(2.0 * std::numbers::pi * frequency[i] * t + phase[i]) - std::sin(phase[i]));
    quake[k] = envelope * sum;
    peak = std::max(peak, std::abs(quake[k]));
  }
  for (std::size_t k = 1; k <= n; ++k) u.push_back(kQuakePeak * quake[k] / peak);
  runtime::Drive drive;
  for (std::size_t k = 0; k < u.size(); ++k) {
    drive.time.push_back(static_cast<double>(k) / kSampleRate);
    drive.displacement.push_back(std::round(u[k] * 1000.0) / 1000.0 + 0.0);  // + 0.0: no "-0.000"
  }
  return drive;
}

// The file's text: comment lines, `Time (s),Displacement (mm),Force (kN)`, time to 10 ms,
// displacement to 1 um, force to 1 N (as kN with three decimals). The measured force is the
// truth's plus kOffset + kDrift t / t_end plus kNoise N(0, 1).
inline std::string csv() {
  std::mt19937 bits(kSeed);
  const runtime::Drive drive = programme(bits);
  const runtime::History h = runtime::run_history(network_from(kTruth, "damper"), drive, false, runtime::SolverChoice::fixed);
  std::string out =
      "# Rig export: friction damper, axial, displacement-controlled\n"
      "# Programme: sines 12 mm 0.25 Hz, 25 mm 0.5 Hz, 38 mm 1 Hz, 20 mm 2 Hz; then a 12 s earthquake record scaled to 30 mm\n"
      "# Load cell not zeroed before the test; sampled at 50 Hz\n"
      "Time (s),Displacement (mm),Force (kN)\n";
  const double end = drive.time.back();
  for (std::size_t k = 0; k < drive.time.size(); ++k) {
    const double measured = h.force[k] + kOffset + kDrift * drive.time[k] / end + kNoise * normal(bits);
    out += fmt::format("{:.2f},{:.3f},{:.3f}\n", drive.time[k], drive.displacement[k], std::round(measured) / 1000.0 + 0.0);
  }
  return out;
}

}  // namespace rheo::test::rig_file
