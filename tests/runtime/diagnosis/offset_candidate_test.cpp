// The effect `offset` (offset_candidate.hpp): a load cell's zero that the data line does not
// state. How the refined file states it (data lines edited byte for byte), and rheo diagnose
// naming it in a history it is hidden in, with the offset recovered, and not where there is none.
#include "runtime/diagnosis/offset_candidate.hpp"

#include "lang/frontend.hpp"
#include "runtime/diagnosis/diagnose.hpp"

#include "../diagnosis_support.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

namespace offset_candidate_test {

using namespace rheo;
namespace dx = runtime::diagnosis;

namespace {

runtime::FitDataSet history_named(const std::string& path) {
  runtime::HistoryData h;
  h.path = path;
  h.drive.time = {0.0, 1.0}, h.drive.displacement = {0.0, 1.0}, h.force = {0.0, 1.0}, h.rows = {2, 3}, h.force_scale = 1.0;
  return {path, 1.0, h};
}

runtime::FitResult refit_with_offsets(const std::vector<runtime::FitDataSet>& data, const std::vector<double>& offsets) {
  runtime::FitResult r;
  for (std::size_t k = 0; k < data.size(); ++k) {
    runtime::DataSetFit set;
    set.path = data[k].path;
    set.force_offset.free = set.force_offset.given = true;
    set.force_offset.value = offsets[k];
    r.datasets.push_back(set);
  }
  return r;
}

// The truth of the diagnose cases: a spring and a friction element (yield 30 N).
const char* kTruth = "model truth { spring s (k = 250 N/mm)  friction f (k = 300 N/mm, fy = 30 N) }";
const char* kStart = "model start {\n  spring s (k = 300 N/mm in [10, 10000])\n  friction f (k = 100 N/mm in [1, 10000], uy = 20 um in [0.1, 10000])\n}\n";

runtime::FitDataSet with_force_offset(runtime::FitDataSet set, double offset) {
  auto& h = std::get<runtime::HistoryData>(set.data);
  for (double& f : h.force) f += offset;
  h.force_scale = 0.0;
  for (double f : h.force) h.force_scale = std::max(h.force_scale, std::abs(f));
  return set;
}

}  // namespace

TEST_CASE("offset candidate: the histories whose offset is not fitted are freed, harmonic tables and free offsets are left") {
  std::vector<runtime::FitDataSet> data{history_named("a.csv"), history_named("b.csv"), history_named("c.csv")};
  data[1].force_offset = {.given = true, .free = true, .value = 0.0};
  data[2].force_offset = {.given = true, .free = false, .value = 120.0};
  runtime::HarmonicData table;
  table.amplitude = {0.1}, table.frequency = {1.0}, table.stiffness = {100.0}, table.phase = {0.1}, table.rows = {2};
  data.push_back({"h.csv", 1.0, table});
  const std::vector<std::size_t> fixed = dx::fixed_offsets(data);
  CHECK(fixed == std::vector<std::size_t>{0, 2});
  const std::vector<runtime::FitDataSet> freed = dx::with_free_offsets(data, fixed);
  CHECK(dx::fixed_offsets(freed).empty());
  CHECK(freed[2].force_offset.free);
  CHECK_FALSE(data[0].force_offset.free);  // the input is not changed
}

TEST_CASE("offset candidate: a data line gets `force_offset = free` after its last setting, a declared value becomes free") {
  const std::string source =
      "model m { spring s (k = 10 N/mm in [1, 100]) }\n"
      "fit m {\n"
      "  data \"a.csv\", weight = 2   # the rig's first run\n"
      "  data \"b.csv\",\n"
      "       force_offset = 120 N\n"
      "}\n";
  const lang::Program program = lang::compile_source("f.rheo", source);
  const std::vector<lang::FitData>& lines = program.fits.at(0).data;
  const std::vector<runtime::FitDataSet> data{history_named("a.csv"), history_named("b.csv")};
  const dx::OffsetText text = dx::offset_text(source, "f.rheo", lines, {0, 1}, refit_with_offsets(data, {-650.25, 40.0}));
  const lang::CheckedModel& m = program.models.front();
  const std::string written = lang::write_fitted_source(source, "f.rheo", m, {10.0}, {}, {}, text.edits);
  CHECK(written ==
        "model m { spring s (k = 10 N/mm in [1, 100]) }\n"
        "fit m {\n"
        "  data \"a.csv\", weight = 2, force_offset = free   # the rig's first run\n"
        "  data \"b.csv\",\n"
        "       force_offset = free\n"
        "}\n");
  const lang::Program again = lang::compile_source("f.rheo", written);  // the refined file checks
  CHECK(again.fits.at(0).data.at(0).force_offset.free);
  CHECK(again.fits.at(0).data.at(1).force_offset.free);
  CHECK(text.statement == std::vector<std::string>{"data \"a.csv\", weight = 2, force_offset = free", "data \"b.csv\",", "force_offset = free"});
  CHECK(text.summary == "data a.csv: force_offset = -650.25 N, data b.csv: force_offset = 40 N");
}

TEST_CASE("offset candidate: data given otherwise (--data) are told how to state the offset") {
  const std::vector<runtime::FitDataSet> data{history_named("run.csv")};
  const dx::OffsetText text = dx::offset_text("model m { spring s (k = 1 N/mm) }\n", "f.rheo", {}, {0}, refit_with_offsets(data, {3.0}));
  CHECK(text.edits.empty());
  CHECK(text.statement == std::vector<std::string>{"--data 'run.csv, force_offset = free'"});
}

TEST_CASE("diagnose, sine history: a load cell's zero of -8 % of the force that no data line states is offset, and it is recovered") {
  const runtime::FitDataSet clean = test::history_measurement(kTruth, runtime::quasistatic_sine({1.0, 0.5}, 0.5, 2, 200), 41);
  const double offset = -0.08 * clean.history().force_scale;
  const dx::Diagnosis d = test::diagnose(kStart, {with_force_offset(clean, offset)});
  INFO(d.reason);
  REQUIRE(d.verdict == dx::Verdict::named);
  CHECK(d.effect == dx::Effect::offset);
  CHECK(d.freed_offsets == std::vector<std::size_t>{0});
  REQUIRE(d.after.has_value());
  CHECK(d.gap_after <= d.gap_before / 3.0);
  // The noise is 0.003 max|F| a sample over 800 samples: the mean's error is ~1e-4 max|F|.
  CHECK(std::abs(d.after->datasets.at(0).force_offset.value - offset) <= 2e-3 * clean.history().force_scale);
  CHECK(d.refined_text.find("effect offset") != std::string::npos);
  CHECK(d.added_statement == std::vector<std::string>{"--data 'hidden_history.csv, force_offset = free'"});
}

TEST_CASE("diagnose, sine history: without an offset, offset is screened and not named, and with every offset fitted it is not screened") {
  const runtime::FitDataSet clean = test::history_measurement(kTruth, runtime::quasistatic_sine({1.0, 0.5}, 0.5, 2, 200), 42);
  const dx::Diagnosis d = test::diagnose(kStart, {clean});
  CHECK(d.effect != dx::Effect::offset);
  CHECK(std::any_of(d.candidates.begin(), d.candidates.end(), [](const dx::CandidateOutcome& c) { return c.screened.effect == dx::Effect::offset; }));
  runtime::FitDataSet fitted = with_force_offset(clean, 25.0);
  fitted.force_offset = {.given = true, .free = true, .value = 0.0};
  const dx::Diagnosis free = test::diagnose(kStart, {fitted}, false, 0);
  CHECK(std::none_of(free.candidates.begin(), free.candidates.end(),
                     [](const dx::CandidateOutcome& c) { return c.screened.effect == dx::Effect::offset; }));
}

}  // namespace offset_candidate_test
