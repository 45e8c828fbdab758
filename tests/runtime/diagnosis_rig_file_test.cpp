// Issue 24's real rig file, rebuilt from a known model (examples/data/friction_damper_rig.csv,
// rig_file_support.hpp): a friction damper with plateaus of +13 kN / -20 kN behind off-centre
// free play, read as the rig wrote it, with a load-cell offset, a drifting zero and noise.
// From `spring || friction` and a free force offset, diagnose names the free play first (its
// residual is largest where the loops turn), then, on the refined model, the one-sided yield;
// the gap falls to the noise the generator put in (the drift adds a little) and the values of
// the generating model come back.
#include "rig_file_support.hpp"

#include "runtime/diagnosis/diagnose.hpp"
#include "runtime/io/fit_data.hpp"
#include "runtime/io/history_csv.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

namespace diagnosis_rig_file_test {

using namespace rheo;
namespace dx = runtime::diagnosis;

namespace {

const char* kStart = R"(model damper {
  spring   s (k = 100 N/mm in [0.1, 100000])
  friction f (k = 1000 N/mm in [1, 1000000], fy = 10000 N in [10, 1000000])
}
)";

runtime::FitDataSet rig_file() {
  const runtime::Table table = runtime::read_table(std::string(RHEO_DATA_DIR) + "/friction_damper_rig.csv");
  runtime::FitDataSet set{table.path, 1.0, runtime::history_data_from_table(table)};
  set.force_offset = {.given = true, .free = true, .value = 0.0};
  return set;
}

double parameter(const dx::Diagnosis& d, const std::string& path) {
  const runtime::Network& n = d.after->network;
  return n.parameter(test::parameter_index(n, path));
}

}  // namespace

TEST_CASE("diagnose on the friction damper's rig file: backlash, then asymmetry, down to the noise") {
  const std::vector<runtime::FitDataSet> data{rig_file()};
  const double largest = data[0].history().force_scale;
  const double noise = test::rig_file::kNoise / largest;  // the gap the generator's noise alone leaves
  dx::DiagnoseSettings settings;
  settings.fit.score.harmonic.solver = runtime::SolverChoice::fixed;  // as rheo diagnose does with solver = auto

  const dx::Diagnosis first = dx::diagnose({"damper.rheo", kStart, "damper"}, data, settings);
  MESSAGE(fmt::format("round 1: {} {:.4g} -> {:.4g}, noise put in {:.4g}", dx::verdict_name(first), first.gap_before, first.gap_after, noise));
  REQUIRE(first.effect == dx::Effect::backlash);
  CHECK(first.gap_before > 20.0 * noise);
  CHECK(first.gap_after < first.gap_before / 1.5);

  const dx::Diagnosis second = dx::diagnose({"damper.rheo", first.refined_text, "damper"}, data, settings);
  MESSAGE(fmt::format("round 2: {} {:.4g} -> {:.4g}", dx::verdict_name(second), second.gap_before, second.gap_after));
  REQUIRE(second.effect == dx::Effect::asymmetry);
  REQUIRE(second.after.has_value());
  // The drift of the zero (150 N over the record, about 43 N RMS about its mean) adds to the
  // 60 N of noise: sqrt(60^2 + 43^2) = 74 N, 1.23 times the noise alone.
  CHECK(second.gap_after < 1.4 * noise);
  CHECK(second.gap_after > noise);
  // The generating model: play 6 mm centred at +1.5 mm, k = 4000 N/mm, caps 13 and 20 kN, the
  // spring 30 N/mm; the offset is the zero's mean over the record, -650 + 150/2 N.
  CHECK(parameter(second, "backlash.play.width") == doctest::Approx(6.0).epsilon(0.02));
  CHECK(parameter(second, "backlash.play.center") == doctest::Approx(1.5).epsilon(0.05));
  CHECK(parameter(second, "backlash.f.k") == doctest::Approx(4000.0).epsilon(0.03));
  CHECK(parameter(second, "backlash.f.fy_pos") == doctest::Approx(13000.0).epsilon(0.01));
  CHECK(parameter(second, "backlash.f.fy_neg") == doctest::Approx(20000.0).epsilon(0.01));
  CHECK(parameter(second, "s.k") == doctest::Approx(30.0).epsilon(0.1));
  CHECK(second.after->datasets[0].prediction.force_offset == doctest::Approx(-575.0).epsilon(0.05));
}

TEST_CASE("refine on the friction damper's rig file with no force offset stated: offset, backlash, asymmetry, then none at the noise") {
  // As issue 24 found the file: `spring || friction`, and nothing on the data line about the
  // load cell's -650 N. Each round as rheo refine runs it: the offsets a round frees are fitted
  // in the next.
  std::vector<runtime::FitDataSet> data{rig_file()};
  data[0].force_offset = {};
  const double noise = test::rig_file::kNoise / data[0].history().force_scale;
  dx::DiagnoseSettings settings;
  settings.fit.score.harmonic.solver = runtime::SolverChoice::fixed;
  std::string text = kStart;
  std::vector<dx::Effect> named;
  std::optional<dx::Diagnosis> last;
  for (int round = 0; round < 5; ++round) {
    last = dx::diagnose({"damper.rheo", text, "damper"}, data, settings);
    MESSAGE(fmt::format("round {}: {} {:.4g} -> {:.4g}", round + 1, dx::verdict_name(*last), last->gap_before, last->gap_after));
    for (std::size_t k : last->freed_offsets) data[k].force_offset = {.given = true, .free = true, .value = 0.0};
    text = last->refined_text;
    if (last->verdict != dx::Verdict::named) break;
    named.push_back(last->effect);
  }
  CHECK(named == std::vector<dx::Effect>{dx::Effect::offset, dx::Effect::backlash, dx::Effect::asymmetry});
  CHECK(last->verdict == dx::Verdict::none);
  CHECK(last->gap_after < 1.4 * noise);  // the drift's 43 N RMS beside the 60 N of noise, as above
  CHECK(last->before.datasets[0].prediction.force_offset == doctest::Approx(-575.0).epsilon(0.05));
}

TEST_CASE("diagnose, the rig file's programme through other values: play and one-sided yield that earn only together") {
  // Caps 20 kN in tension and 12 kN in compression behind 4 mm of play centred at -1 mm, a
  // 50 N/mm spring, 100 N of noise and a +300 N zero, another earthquake record: here neither
  // the play nor the asymmetry lowers the gap by a quarter alone (each leaves the other's
  // residual), so diagnose refits them together in the friction element.
  const char* truth = R"(model damper {
  spring s (k = 50 N/mm)
  series stop { gap play (width = 4 mm, center = -1 mm)  friction f (k = 2500 N/mm, fy_pos = 20000 N, fy_neg = 12000 N) }
})";
  std::mt19937 bits(test::rig_file::kSeed + 1);
  const runtime::Drive drive = test::rig_file::programme(bits);
  const runtime::History h = runtime::run_history(test::network_from(truth, "damper"), drive, false, runtime::SolverChoice::fixed);
  runtime::HistoryData data;
  data.path = "other_damper.csv";
  data.drive = drive;
  for (double f : h.force) data.force.push_back(f + 300.0 + 100.0 * test::rig_file::normal(bits));
  data.rows.assign(data.force.size(), 0);
  for (double f : data.force) data.force_scale = std::max(data.force_scale, std::abs(f));
  runtime::FitDataSet set{data.path, 1.0, data};
  set.force_offset = {.given = true, .free = true, .value = 0.0};
  dx::DiagnoseSettings settings;
  settings.fit.score.harmonic.solver = runtime::SolverChoice::fixed;
  const double noise = 100.0 / data.force_scale;

  const dx::Diagnosis d = dx::diagnose({"damper.rheo", kStart, "damper"}, {set}, settings);
  MESSAGE(fmt::format("{} {:.4g} -> {:.4g}, noise put in {:.4g}", dx::verdict_name(d), d.gap_before, d.gap_after, noise));
  const auto together = std::find_if(d.candidates.begin(), d.candidates.end(), [](const dx::CandidateOutcome& c) { return c.chosen; });
  REQUIRE(together != d.candidates.end());
  CHECK(together->limit_of.find("neither earned alone") != std::string::npos);
  // The reason names what was screened (it named a slider-capped fluid column for every refit
  // that was not the screen's own).
  CHECK(d.reason.find(together->screened_as + " alone would remove") != std::string::npos);
  CHECK(d.reason.find("fluid column") == std::string::npos);
  // Its refitted values (CandidateOutcome::fitted; JSON candidates[].fitted), before the polish.
  CAPTURE(together->fitted);
  const auto written = [&](const std::string& path) {
    const std::size_t at = together->fitted.find(path + " = ");
    return at == std::string::npos ? 0.0 : std::stod(together->fitted.substr(at + path.size() + 3));
  };
  // Before the polish the centre sat at the play's edge (-w/2: the stop touching at rest), which the polish leaves.
  CHECK(written("backlash.play.width") == doctest::Approx(4.0).epsilon(0.05));
  CHECK(written("backlash.play.center") < -0.9);
  CHECK(written("backlash.f.fy_pos") == doctest::Approx(20000.0).epsilon(0.02));
  CHECK(together->fitted.find("backlash.f.fy_neg = ") != std::string::npos);
  for (const dx::CandidateOutcome& c : d.candidates)  // alone, none earned its parameters
    if (c.refitted && !c.chosen) CHECK(c.gap_after > 0.75 * d.gap_before);
  REQUIRE(d.after.has_value());
  CHECK(d.gap_after < 1.2 * noise);
  CHECK(parameter(d, "backlash.play.width") == doctest::Approx(4.0).epsilon(0.02));
  CHECK(parameter(d, "backlash.play.center") == doctest::Approx(-1.0).epsilon(0.05));
  CHECK(parameter(d, "backlash.f.fy_pos") == doctest::Approx(20000.0).epsilon(0.01));
  CHECK(parameter(d, "backlash.f.fy_neg") == doctest::Approx(12000.0).epsilon(0.01));
  CHECK(d.refined_text.find("series backlash") != std::string::npos);
}

}  // namespace diagnosis_rig_file_test
