// Conformance of exported FMUs with an independent FMI host (#27 item 2): fmusim, the FMI
// Reference FMUs' simulator, validates each FMU's modelDescription.xml against the FMI 2.0 schema,
// loads its binary and runs it as co-simulation on a displacement history, holding each input
// over the step. Its force must be rheo's own, `rheo simulate --solver fixed` on the same held
// (staircase) history, within 1e-7 of the largest |F|; with logging on nothing may be logged.
// The staircase is written for rheo as a history whose input ramps to the next value over the
// first part of each step: h/2^10, the FMU's own ramp, for networks with subtrees; h/2^20 for a
// network all in the model's body, where the FMU jumps exactly and a ramp of h/2^20 differs from
// the jump by 2^-21 h/tau of a Maxwell arm's jump force (runtime/fmu/cosimulation.hpp;
// docs/numerics.md#fmu-input-between-communication-points). The step is 2^-11 s, so that every
// time fmusim and rheo form is exact in binary.
#include "cli_support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

constexpr double kStep = 1.0 / 2048.0;  // s, the communication step
constexpr int kSteps = 2000;

// fmusim, built by the fixture test fmusim_build (tests/CMakeLists.txt); false (failing under CI)
// when it could not be.
bool fmusim_available() {
  if (fs::exists(FMUSIM_BINARY)) return true;
  const std::string advice = fmt::format("fmusim was not built ({}; see the test fmusim_build)", FMUSIM_BINARY);
  if (rheo::test::in_ci()) FAIL_CHECK(advice << ": CI needs it");
  else MESSAGE("SKIPPED: " << advice);
  return false;
}

std::string text_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string run(const std::string& command) {
  std::string out;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  REQUIRE(pipe != nullptr);
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  CHECK_MESSAGE(pclose(pipe) == 0, command << "\n" << out);
  return out;
}

// Column COLUMN of a CSV file's numeric rows (rows starting with a digit or sign).
std::vector<double> column(const fs::path& path, int column) {
  std::ifstream in(path);
  std::vector<double> values;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || !(std::isdigit(static_cast<unsigned char>(line[0])) || line[0] == '-')) continue;
    std::stringstream cells(line);
    std::string cell;
    for (int i = 0; i <= column; ++i) std::getline(cells, cell, ',');
    values.push_back(std::stod(cell));
  }
  return values;
}

double displacement(int n) {
  const double t = n * kStep;
  return 1.2 * std::sin(2 * std::numbers::pi * 3.0 * t) + 0.3 * std::sin(2 * std::numbers::pi * 17.0 * t) + 0.2 * t;
}

struct Comparison {
  double peak = 0.0, worst = 0.0;
  std::string log;
};

// Exports MODEL of SOURCE, runs it in fmusim on the sampled displacement and rheo on the held
// history (ramps of RAMP h); the largest |F| and the largest difference.
Comparison compare(const std::string& name, const std::string& source, const std::string& model, double ramp) {
  const fs::path dir = rheo::test::scratch_directory("fmusim-" + name);
  std::ofstream(dir / "model.rheo") << source << "\nsimulate " << model
                                    << " {\n  history file = \"held.csv\", solver = fixed\n  output \"rheo.csv\"\n}\n";
  const auto exported = rheo::test::run_rheo(
      fmt::format("export {} --fmu {} --model {}", (dir / "model.rheo").string(), (dir / "m.fmu").string(), model));
  REQUIRE_MESSAGE(exported.code == 0, exported.err);
  {
    std::ofstream in(dir / "in.csv"), held(dir / "held.csv");
    in << "\"time\",\"u\"\n";
    held << "time [s],displacement [mm]\n" << fmt::format("0,{:.17g}\n", displacement(0));
    for (int n = 0; n <= kSteps; ++n) {
      in << fmt::format("{:.17g},{:.17g}\n", n * kStep, displacement(n));
      if (n == 0) continue;
      // Held at u(n-1) until t_n, then the jump to u(n).
      held << fmt::format("{:.17g},{:.17g}\n{:.17g},{:.17g}\n", n * kStep, displacement(n - 1), n * kStep + ramp * kStep, displacement(n));
    }
  }
  Comparison c;
  c.log = run(
      fmt::format("cd {} && {} --interface-type cs --logging-on --log-level ok --log-fmi-calls --fmi-log-file calls.log --input-file in.csv "
                  "--output-interval {} --stop-time {} --output-variable F --output-file fmusim.csv m.fmu",
                  dir.string(), FMUSIM_BINARY, kStep, kSteps * kStep));
  const std::string calls = text_of((dir / "calls.log").string());
  CHECK(calls.find("fmi2DoStep(") != std::string::npos);
  for (const char* bad : {"-> Warning", "-> Discard", "-> Error", "-> Fatal"}) CHECK_MESSAGE(calls.find(bad) == std::string::npos, bad);
  const auto simulated = rheo::test::run_rheo(fmt::format("simulate {}", (dir / "model.rheo").string()));
  REQUIRE_MESSAGE(simulated.code == 0, simulated.err);
  const std::vector<double> fmu = column(dir / "fmusim.csv", 1), rheo = column(dir / "rheo.csv", 2);
  REQUIRE(fmu.size() == static_cast<std::size_t>(kSteps + 1));
  REQUIRE(rheo.size() == static_cast<std::size_t>(2 * kSteps + 1));
  // fmusim's row n is the force at t_n; rheo's at t_n, held at u(n-1), is row 2n - 1 (row 0: t = 0).
  for (int n = 0; n <= kSteps; ++n) {
    const double reference = rheo[static_cast<std::size_t>(n == 0 ? 0 : 2 * n - 1)];
    c.peak = std::max(c.peak, std::abs(reference));
    c.worst = std::max(c.worst, std::abs(fmu[static_cast<std::size_t>(n)] - reference));
  }
  fs::remove_all(dir);
  return c;
}

std::string example(const std::string& file) { return text_of(std::string(RHEO_EXAMPLES_DIR) + "/" + file); }

}  // namespace

TEST_CASE("fmusim runs specimen D's FMU: valid, silent, and rheo's force on the held history within 1e-7") {
  if (!fmusim_available()) return;
  const Comparison c = compare("specimen-d", example("specimen_d.rheo"), "specimen_d", 1.0 / 1048576.0);
  CHECK(c.log.empty());
  CHECK(c.peak > 500.0);
  CHECK(c.worst <= 1e-7 * c.peak);
  MESSAGE(fmt::format("specimen D: max |F| {:.6g} N, max difference {:.3g} N ({:.2g} of it)", c.peak, c.worst, c.worst / c.peak));
}

TEST_CASE("fmusim runs the hydrobushing's FMU: valid, silent, and rheo's force on the held history within 1e-7") {
  if (!fmusim_available()) return;
  const Comparison c = compare("hydrobushing", example("hydrobushing.rheo"), "hydrobushing", 1.0 / 1024.0);
  CHECK(c.log.empty());
  CHECK(c.peak > 500.0);
  CHECK(c.worst <= 1e-7 * c.peak);
  MESSAGE(fmt::format("hydrobushing: max |F| {:.6g} N, max difference {:.3g} N ({:.2g} of it)", c.peak, c.worst, c.worst / c.peak));
}

TEST_CASE("fmusim runs a Bouc-Wen damper's FMU: valid, silent, and rheo's force on the held history within 1e-7") {
  if (!fmusim_available()) return;
  const std::string source =
      "# A smooth-friction damper: rubber, a Bouc-Wen element and a Maxwell arm in parallel.\n"
      "model bouc_wen_damper {\n  spring rubber (k = 200 N/mm)\n  bouc_wen slip (k = 800 N/mm, n = 1.5, fy = 60 N)\n"
      "  maxwell visco (k = 120 N/mm, tau = 6 ms)\n}\n";
  const Comparison c = compare("bouc-wen", source, "bouc_wen_damper", 1.0 / 1024.0);
  CHECK(c.log.empty());
  CHECK(c.peak > 200.0);
  CHECK(c.worst <= 1e-7 * c.peak);
  MESSAGE(fmt::format("bouc_wen: max |F| {:.6g} N, max difference {:.3g} N ({:.2g} of it)", c.peak, c.worst, c.worst / c.peak));
}

TEST_CASE("fmusim drives the hydrobushing's FMU with its velocity input v: rheo's force on the linear history within 1e-9") {
  if (!fmusim_available()) return;
  // A host that provides the velocity over each step, v_n = (u_{n+1} - u_n)/h, gives the FMU the
  // piecewise-linear drive that rheo simulates: no lag, one kernel pass per step.
  const fs::path dir = rheo::test::scratch_directory("fmusim-velocity");
  std::ofstream(dir / "model.rheo") << example("hydrobushing.rheo")
                                    << "\nsimulate hydrobushing {\n  history file = \"linear.csv\", solver = fixed\n  output \"rheo.csv\"\n}\n";
  REQUIRE(rheo::test::run_rheo(fmt::format("export {} --fmu {}", (dir / "model.rheo").string(), (dir / "m.fmu").string())).code == 0);
  {
    std::ofstream in(dir / "in.csv"), linear(dir / "linear.csv");
    in << "\"time\",\"u\",\"v\"\n";
    linear << "time [s],displacement [mm]\n";
    for (int n = 0; n <= kSteps; ++n) {
      const double v = n < kSteps ? (displacement(n + 1) - displacement(n)) / kStep : 0.0;
      in << fmt::format("{:.17g},{:.17g},{:.17g}\n", n * kStep, displacement(n), v);
      linear << fmt::format("{:.17g},{:.17g}\n", n * kStep, displacement(n));
    }
  }
  const std::string log = run(
      fmt::format("cd {} && {} --interface-type cs --logging-on --log-level ok --input-file in.csv --output-interval {} "
                  "--stop-time {} --output-variable F --output-file fmusim.csv m.fmu",
                  dir.string(), FMUSIM_BINARY, kStep, kSteps * kStep));
  CHECK(log.empty());
  REQUIRE(rheo::test::run_rheo(fmt::format("simulate {}", (dir / "model.rheo").string())).code == 0);
  const std::vector<double> fmu = column(dir / "fmusim.csv", 1), rheo = column(dir / "rheo.csv", 2);
  REQUIRE(fmu.size() == static_cast<std::size_t>(kSteps + 1));
  REQUIRE(rheo.size() == fmu.size());
  double peak = 0.0, worst = 0.0;
  for (std::size_t n = 0; n < fmu.size(); ++n) {
    peak = std::max(peak, std::abs(rheo[n]));
    worst = std::max(worst, std::abs(fmu[n] - rheo[n]));
  }
  MESSAGE(fmt::format("hydrobushing with v: max |F| {:.6g} N, max difference {:.3g} N ({:.2g} of it)", peak, worst, worst / peak));
  CHECK(peak > 500.0);
  CHECK(worst <= 1e-9 * peak);
  fs::remove_all(dir);
}

TEST_CASE("fmusim continues a run from the FMU state another run saved, bit for bit as if it had not stopped") {
  if (!fmusim_available()) return;
  const fs::path dir = rheo::test::scratch_directory("fmusim-state");
  const auto exported = rheo::test::run_rheo(fmt::format("export {}/hydrobushing.rheo --fmu {}", RHEO_EXAMPLES_DIR, (dir / "h.fmu").string()));
  REQUIRE(exported.code == 0);
  {
    std::ofstream in(dir / "in.csv");
    in << "\"time\",\"u\"\n";
    for (int n = 0; n <= 400; ++n) in << fmt::format("{:.17g},{:.17g}\n", n * kStep, displacement(n));
  }
  const std::string common = fmt::format("cd {} && {} --interface-type cs --input-file in.csv --output-interval {} --output-variable F",
                                         dir.string(), FMUSIM_BINARY, kStep);
  run(fmt::format("{} --stop-time {} --output-file whole.csv h.fmu", common, 400 * kStep));
  run(fmt::format("{} --stop-time {} --final-fmu-state-file state.bin --output-file first.csv h.fmu", common, 200 * kStep));
  run(fmt::format("{} --start-time {} --stop-time {} --initial-fmu-state-file state.bin --output-file second.csv h.fmu", common, 200 * kStep,
                  400 * kStep));
  const auto whole = column(dir / "whole.csv", 1), first = column(dir / "first.csv", 1), second = column(dir / "second.csv", 1);
  REQUIRE(whole.size() == 401);
  REQUIRE(first.size() == 201);
  REQUIRE(second.size() == 201);
  double peak = 0.0, worst = 0.0;
  for (std::size_t n = 0; n <= 200; ++n) {
    CHECK(first[n] == whole[n]);
    peak = std::max(peak, std::abs(whole[200 + n]));
    worst = std::max(worst, std::abs(second[n] - whole[200 + n]));
  }
  CHECK(peak > 500.0);
  CHECK(worst == 0.0);
  fs::remove_all(dir);
}
