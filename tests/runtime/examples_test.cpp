// Every example runs through the real binary (the last test case lists them, so none is left
// out; the fits, diagnoses and refinements are in examples_fit_test.cpp), and its key numbers
// are checked against closed forms, the documented numbers and the reference data of
// examples/data (README.md there): the Appendix D models reproduce the noise-free harmonic grids
// within what those files guarantee (1e-5 relative in stiffness and 2e-4 deg in phase of the
// exact steady state, each written to 4 decimals), and specimen D's static and quasi-static
// tests within the stated force noise (0.3 % of the maximum). Numbers that come from rheo's own
// output (the README's row) are regression checks, named so, each beside an independent check
// of the same quantity.
#include "examples_support.hpp"
#include "parallel_closed_form.hpp"
#include "support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace examples_test {

using namespace rheo;
using namespace rheo::test::examples;

namespace {

// The worst deviation of the simulated grid of RHEO_FILE from the noise-free REFERENCE, each as
// a fraction of what the file guarantees: relative STIFFNESS_ACCURACY and PHASE_ACCURACY [deg] of
// the exact steady state (examples/data/README.md), plus half a unit of the 4th decimal each
// value is written to (5e-5 N/mm, 5e-5 deg). rheo's closed form is exact to rounding, so a
// fraction above 1 is an error in rheo, not in the data.
struct GridDeviation {
  double stiffness = 0.0, phase = 0.0;  // worst |error| / bound
};
GridDeviation compare_harmonic(const std::string& rheo_file, const std::string& reference, double stiffness_accuracy, double phase_accuracy) {
  const fs::path out = scratch() / (fs::path(rheo_file).stem().string() + "_harmonic.csv");
  REQUIRE(rheo_run(fmt::format("simulate {} --protocol harmonic -o {}", example(rheo_file), out.string())) == 0);
  const runtime::Table got = runtime::read_table(out.string());
  const runtime::Table want = runtime::read_table(data(reference));
  REQUIRE(got.rows.size() == want.rows.size());
  constexpr double half_digit = 0.5e-4;
  GridDeviation worst;
  for (std::size_t i = 0; i < want.rows.size(); ++i) {
    REQUIRE(std::abs(got.columns[0][i] - want.columns[0][i]) < 1e-9);  // amplitude
    REQUIRE(std::abs(got.columns[1][i] - want.columns[1][i]) < 1e-9);  // frequency
    const double stiffness = want.columns[2][i], phase_deg = want.columns[3][i] * 180.0 / M_PI;
    worst.stiffness = std::max(worst.stiffness, std::abs(got.columns[2][i] - stiffness) / (stiffness_accuracy * stiffness + half_digit));
    worst.phase = std::max(worst.phase, std::abs(got.columns[3][i] * 180.0 / M_PI - phase_deg) / (phase_accuracy + half_digit));
  }
  CAPTURE(rheo_file);
  CHECK(worst.stiffness <= 1.0);
  CHECK(worst.phase <= 1.0);
  MESSAGE(fmt::format("{}: worst stiffness error {:.2f} and worst phase error {:.2f} of what {} guarantees", rheo_file, worst.stiffness,
                      worst.phase, reference));
  return worst;
}
void compare_specimen(const std::string& rheo_file, const std::string& reference) { compare_harmonic(rheo_file, reference, 1e-5, 2e-4); }

// Residual of a simulated history against a measured one, RMS relative to the largest force.
double relative_rms_residual(const std::string& simulated, const std::string& measured) {
  const runtime::Table got = runtime::read_table(simulated);
  const runtime::Table want = runtime::read_table(measured);
  REQUIRE(got.rows.size() == want.rows.size());
  double sum = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < want.rows.size(); ++i) {
    REQUIRE(std::abs(got.columns[1][i] - want.columns[1][i]) < 1e-5);  // same displacement programme
    const double r = got.columns[2][i] - want.columns[2][i];
    sum += r * r;
    largest = std::max(largest, std::abs(want.columns[2][i]));
  }
  return std::sqrt(sum / static_cast<double>(want.rows.size())) / largest;
}

}  // namespace

TEST_CASE("specimen A reproduces its reference harmonic grid to the file's accuracy") {
  compare_specimen("specimen_a.rheo", "specimen_A_reference.csv");
}
TEST_CASE("specimen B reproduces its reference harmonic grid to the file's accuracy") {
  compare_specimen("specimen_b.rheo", "specimen_B_reference.csv");
}
TEST_CASE("specimen C reproduces its reference harmonic grid to the file's accuracy") {
  compare_specimen("specimen_c.rheo", "specimen_C_reference.csv");
}
TEST_CASE("specimen D reproduces its reference harmonic grid to the file's accuracy") {
  compare_specimen("specimen_d.rheo", "specimen_D_reference.csv");
}

TEST_CASE("specimen D static and quasi-static tests agree with the data within its noise") {
  const fs::path dir = scratch();
  for (const char* protocol : {"static", "quasistatic"}) {
    const fs::path out = dir / fmt::format("d_{}.csv", protocol);
    REQUIRE(rheo_run(fmt::format("simulate {} --protocol {} -o {}", example("specimen_d.rheo"), protocol, out.string())) == 0);
    const double residual = relative_rms_residual(out.string(), data(std::string("specimen_D_") + protocol + ".csv"));
    CAPTURE(protocol);
    // The data carry Gaussian force noise of 0.3 % of the maximum: the residual must be that noise.
    CHECK(residual > 0.0025);
    CHECK(residual < 0.0035);
  }
}

TEST_CASE("the README example runs as written and writes the thesis-format grid") {
  const fs::path dir = scratch();
  fs::copy_file(example("bushing_d.rheo"), dir / "bushing_d.rheo", fs::copy_options::overwrite_existing);
  REQUIRE(rheo_run(fmt::format("simulate {}", (dir / "bushing_d.rheo").string())) == 0);
  const runtime::Table t = runtime::read_table((dir / "bushing_d_harmonic.csv").string());
  CHECK(t.rows.size() == 26 * 4);
  CHECK(t.names[0] == "amplitude");
  CHECK(t.units[2] == "N/mm");
  CHECK(t.names[3] == "phase");
  const int converged = t.column("converged");
  for (double c : t.columns[static_cast<std::size_t>(converged)]) CHECK(c == 1.0);
}

// The event-driven periodic state of the fluid column (solver = auto) is exact; the file is
// accurate to about 0.06 % and 0.03 deg (examples/data/README.md). dae_protocols_test runs the
// same grid on IDA.
TEST_CASE("examples/hydrobushing.rheo reproduces hydrobushing_reference.csv to the file's accuracy, 0.06 % and 0.03 deg") {
  compare_harmonic("hydrobushing.rheo", "hydrobushing_reference.csv", 6e-4, 0.03);
}

TEST_CASE("examples/hydromount.rheo: at 0.05 mm its cap holds and the grid is K* of the uncapped mount, at 2 mm F^ <= k_rubber u0 + fy") {
  const fs::path out = scratch() / "hydromount_harmonic.csv";
  REQUIRE(rheo_run(fmt::format("simulate {} -o {}", example("hydromount.rheo"), out.string())) == 0);
  const runtime::Table t = runtime::read_table(out.string());
  REQUIRE(t.rows.size() == 3 * 8);
  int small = 0, large = 0;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const double u0 = t.columns[0][i], w = 2.0 * M_PI * t.columns[1][i], stiffness = t.columns[2][i], phase = t.columns[3][i];
    CAPTURE(u0);
    CAPTURE(t.columns[1][i]);
    if (u0 == 0.05) {  // stdlib/hydromount.rheo: k_rubber 800, k1 600, b 40 kg = 0.04 N*s^2/mm, c 3, k2 150
      const std::complex<double> k_star = 800.0 + 1.0 / (1.0 / 600.0 + 1.0 / std::complex<double>{150.0 - 0.04 * w * w, 3.0 * w});
      CHECK(std::abs(stiffness / std::abs(k_star) - 1.0) < 1e-5);
      CHECK(std::abs(phase - std::arg(k_star)) * 180.0 / M_PI < 1e-3);
      ++small;
    } else if (u0 == 2.0) {  // the slider slips: the fluid adds at most fy = 60 N, and the resonance peak is gone
      CHECK(stiffness <= (800.0 * 2.0 + 60.0) / 2.0 * (1.0 + 1e-6));
      CHECK(stiffness >= 800.0);
      CHECK(phase * 180.0 / M_PI < 3.0);
      ++large;
    }
  }
  CHECK(small == 8);
  CHECK(large == 8);
}

// The README's row is rheo's own output (a regression check); the same point in closed form,
// composed from the element laws of examples/bushing_d.rheo (parallel_closed_form.hpp: eq. 3.3,
// B.58, C.13, C.20, thesis definitions), must give it to the 6 decimals printed.
TEST_CASE("regression: the README's 30-second example prints the first row the README shows, which the closed form confirms") {
  const fs::path dir = scratch() / "readme";
  fs::create_directories(dir);
  fs::copy_file(example("bushing_d.rheo"), dir / "bushing_d.rheo", fs::copy_options::overwrite_existing);
  REQUIRE(rheo_run(fmt::format("simulate {} > /dev/null 2>&1", (dir / "bushing_d.rheo").string())) == 0);
  std::ifstream csv(dir / "bushing_d_harmonic.csv");
  std::string line;
  for (int i = 0; i < 4; ++i) std::getline(csv, line);  // two comment lines, the header, the first row
  const std::string first_four = line.substr(0, line.find(',', line.find(',', line.find(',', line.find(',') + 1) + 1) + 1));
  std::ifstream readme(fmt::format("{}/README.md", RHEO_SOURCE_DIR));
  const std::string text((std::istreambuf_iterator<char>(readme)), std::istreambuf_iterator<char>());
  CHECK(first_four == "0.2,1,1358.505496,16.641805");  // regression: rheo's output as the README shows it
  CHECK(text.find("\n" + first_four + "\n") != std::string::npos);
  // Independent: yeoh (389.43, -2.1094, 0.0786), Maxwell (61.476 N/mm, 4.335 ms), friction
  // (1016.6 N/mm, 101.58 um) and (301.04 N/mm, 42.256 um), both slipping at 0.2 mm and 1 Hz.
  const test::Measures want = test::parallel_closed_form([](double u) { return test::yeoh_force(389.43, -2.1094, 0.0786, u); },
                                                         {{61.476, 4.335e-3}}, {{1016.6, 0.10158}, {301.04, 0.042256}}, 0.2, 1.0);
  CHECK(std::abs(want.stiffness - 1358.505496) <= 5e-7 + 1e-9 * want.stiffness);  // printed to 1e-6 N/mm
  CHECK(std::abs(test::degrees(want.phase) - 16.641805) <= 5e-7 + 1e-7);          // printed to 1e-6 deg
}

TEST_CASE("every example is run by a test: a new one fails here until it is") {
  // Examples checked elsewhere: examples_fit_test (the fits, diagnoses and refinements),
  // cli_fit_test (specimen_d_methods.rheo), stdlib_test.
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(RHEO_EXAMPLES_DIR))
    if (const std::string name = entry.path().filename().string(); entry.path().extension() == ".rheo" && !name.ends_with("_fitted.rheo"))
      names.push_back(name);  // *_fitted.rheo: written by the example fits, not in the repository (examples/.gitignore)
  std::sort(names.begin(), names.end());
  CHECK(names == std::vector<std::string>{
                     "bushing_d.rheo",       "coupled_bushing_fit.rheo", "dma_master_curve_fit.rheo", "friction_damper_refine.rheo",
                     "hydrobushing.rheo",    "hydrobushing_fit.rheo",    "hydromount.rheo",           "prony_fit.rheo",
                     "rig_history_fit.rheo", "specimen_a.rheo",          "specimen_a_fit.rheo",       "specimen_b.rheo",
                     "specimen_b_fit.rheo",  "specimen_c.rheo",          "specimen_c_fit.rheo",       "specimen_d.rheo",
                     "specimen_d_fit.rheo",  "specimen_d_fit_all.rheo",  "specimen_d_methods.rheo",   "trios_amplitude_sweep_fit.rheo"});
}

}  // namespace examples_test
