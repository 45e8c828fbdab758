// The reproducers of issue 26 (tests/corpus/repro/backends/, README there) through the binary:
// each network `check` accepts runs on the integrator the file's run would use, and where IDA
// cannot integrate it, `check` and `simulate --solver sundials` refuse it at the element,
// naming the rule (docs/errors.md "Networks that cannot be simulated"), and fixed steps run it.
#include "cli_support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using rheo::test::BinaryRun;
using rheo::test::run_rheo;

namespace {

std::string repro(const std::string& name) { return (fs::path(RHEO_CORPUS_DIR) / "repro" / "backends" / (name + ".rheo")).string(); }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The history the binary writes to standard output: time, displacement, force per row.
struct Rows {
  std::vector<double> time, displacement, force;
};

Rows history_of(const BinaryRun& run) {
  Rows rows;
  std::istringstream in(run.out);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || (!std::isdigit(static_cast<unsigned char>(line[0])) && line[0] != '-')) continue;  // comments, header
    double t = 0.0, u = 0.0, f = 0.0;
    char comma = 0;
    std::istringstream row(line);
    row >> t >> comma >> u >> comma >> f;
    rows.time.push_back(t);
    rows.displacement.push_back(u);
    rows.force.push_back(f);
  }
  return rows;
}

Rows history(const std::string& name, const std::string& solver) {
  const BinaryRun run = run_rheo(fmt::format("simulate {} --protocol history --solver {} -o -", repro(name), solver));
  INFO(run.err);
  REQUIRE(run.code == 0);
  const Rows rows = history_of(run);
  REQUIRE(rows.force.size() == 1001);  // drive.csv: 0 .. 1 s at 1 kHz
  for (double f : rows.force) REQUIRE(std::isfinite(f));
  return rows;
}

// Largest difference of the two histories' forces, relative to the largest |F|.
double difference(const Rows& a, const Rows& b) {
  double scale = 0.0, worst = 0.0;
  for (std::size_t j = 0; j < a.force.size(); ++j) {
    scale = std::max(scale, std::abs(a.force[j]));
    worst = std::max(worst, std::abs(a.force[j] - b.force[j]));
  }
  return worst / scale;
}

void check_refused_on_ida(const std::string& name, const std::string& element_rule) {
  const BinaryRun run = run_rheo(fmt::format("simulate {} --protocol history --solver sundials -o -", repro(name)));
  CHECK(run.code == 3);
  CHECK(contains(run.err, element_rule));
  CHECK(contains(run.err, "use solver = fixed"));
  CHECK(run.out.empty());
}

}  // namespace

TEST_CASE("repro backends 01: a slider in the model's body is refused by check under solver = sundials, fixed steps run it") {
  const BinaryRun check = run_rheo("check " + repro("01_root_slider_sundials"));
  CHECK(check.code == 3);
  CHECK(contains(check.err, "01_root_slider_sundials.rheo:3:3: error: slider 'slider"));
  CHECK(contains(check.err, "sits directly between the terminal and ground"));
  CHECK(contains(check.err, "use solver = fixed"));
  const Rows fixed = history("01_root_slider_sundials", "fixed");
  // F = k u + fy in the direction of the drive's rate (drive.csv rises to 0.5 s, then falls).
  for (std::size_t j : {1U, 100U, 400U, 600U, 900U}) {
    CAPTURE(j);
    const double direction = fixed.displacement[j] > fixed.displacement[j - 1] ? 1.0 : -1.0;
    CHECK(fixed.force[j] == doctest::Approx(100.0 * fixed.displacement[j] + 5.0 * direction).epsilon(1e-9));
  }
}

TEST_CASE("repro backends 02 and 03: bouc_wen behind a slider or a gap is refused on IDA naming the rule, auto runs fixed steps") {
  check_refused_on_ida("02_bouc_wen_slider_sundials", "sits inside a block of a network with sliders, gaps or friction elements");
  check_refused_on_ida("03_gap_bouc_wen_sundials", "sits inside a block of a network with sliders, gaps or friction elements");
  for (const char* name : {"02_bouc_wen_slider_sundials", "03_gap_bouc_wen_sundials"}) {
    CAPTURE(name);
    CHECK(run_rheo(fmt::format("check {}", repro(name))).code == 0);
    (void)history(name, "auto");
  }
}

TEST_CASE("repro backends 05 and 06: check refuses where the run would use IDA, and accepts where auto takes fixed steps") {
  const BinaryRun inerter = run_rheo("check " + repro("05_fixed_slow_gap_boucwen_inerter"));  // auto: IDA for the inerter
  CHECK(inerter.code == 3);
  CHECK(contains(inerter.err, "05_fixed_slow_gap_boucwen_inerter.rheo:6:9: error: bouc_wen 'bouc_wen1'"));
  CHECK(contains(inerter.err, "use solver = fixed"));
  CHECK(run_rheo("check " + repro("06_fixed_slow_boucwen_yeoh_friction")).code == 0);  // auto: fixed steps
  check_refused_on_ida("06_fixed_slow_boucwen_yeoh_friction", "sits inside a block of a network with sliders, gaps or friction elements");
}

// Fixed steps are first order in nested dashpots at the file's 1 ms samples: observed 3.4e-4
// (07), 1.3e-4 (10) and 3.5e-4 (09) of max |F|.
TEST_CASE("repro backends 07 and 10: the histories of bouc_wen + Maxwell and of depth-8 nesting agree between the integrators") {
  CHECK(difference(history("07_fixed_harmonic_noconv_boucwen_maxwell", "fixed"), history("07_fixed_harmonic_noconv_boucwen_maxwell", "sundials")) <
        2e-3);
  CHECK(difference(history("10_deep8_fixed_slow", "fixed"), history("10_deep8_fixed_slow", "sundials")) < 2e-3);
}

TEST_CASE("repro backends 08: a lone dashpot's forces agree sample for sample between the integrators") {
  const Rows fixed = history("08_dashpot_sample_convention", "fixed"), ida = history("08_dashpot_sample_convention", "sundials");
  CHECK(difference(fixed, ida) < 1e-8);
  // The left limit at each sample: c times the rate of the piece ending there.
  for (std::size_t j = 1; j < fixed.force.size(); j += 97) {
    CAPTURE(j);
    const double rate = (fixed.displacement[j] - fixed.displacement[j - 1]) / (fixed.time[j] - fixed.time[j - 1]);
    CHECK(ida.force[j] == doctest::Approx(0.119303 * rate).epsilon(1e-6));
  }
}

TEST_CASE("repro backends 09: the undamped mass behind a slider runs its history on both integrators") {
  CHECK(difference(history("09_undamped_inerter_harmonic", "fixed"), history("09_undamped_inerter_harmonic", "sundials")) < 2e-3);
}
