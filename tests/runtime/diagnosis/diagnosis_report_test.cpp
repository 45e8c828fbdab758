// runtime/diagnosis/diagnosis_report.hpp: the reports of `rheo diagnose` say which parameters
// of the refitted model ended at a bound, as `rheo fit`'s does, and the JSON which effects the
// data do not tell apart from the one named.
#include "runtime/diagnosis/diagnosis_report.hpp"

#include "support.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

namespace diagnosis_report_test {

using namespace rheo;
namespace dx = rheo::runtime::diagnosis;

TEST_CASE("the diagnosis reports name an added parameter the refit left at its bound") {
  const runtime::Network before = test::network_from("model m { spring s (k = 100 in [1, 1000]) }", "m");
  const runtime::Network after = test::network_from(
      "model m { spring s (k = 100 in [1, 1000])\n maxwell m3 (k = 40 N/mm in [1, 10000], tau = 9999.93 ms in [0.01, 10000]) }", "m");
  // Every member named: -Wmissing-field-initializers.
  dx::Diagnosis d{.verdict = dx::Verdict::named,
                  .effect = dx::Effect::rate_dependence,
                  .reason = {},
                  .alike = {dx::Effect::amplitude_dependence},
                  .patterns = {},
                  .noise = {},
                  .noise_ratio = 0.0,
                  .unexplained = {},
                  .before = {.network = before, .free = runtime::bounded_parameters(before), .start_values = before.parameters()},
                  .after = runtime::FitResult{.network = after, .free = runtime::bounded_parameters(after), .start_values = after.parameters()},
                  .gap_name = "err (6.1)",
                  .gap_before = 2e-3,
                  .gap_after = 1e-3,
                  .residual_terms = 0,
                  .criterion_before = 0.0,
                  .candidates = {},
                  .added_element = "m3",
                  .added_summary = {},
                  .added_statement = {"maxwell m3 (k = 40 N/mm in [1, 10000], tau = 9999.93 ms in [0.01, 10000])"},
                  .freed_offsets = {},
                  .refined_text = {},
                  .interrupted = false,
                  .time_limited = false,
                  .before_program = {},
                  .after_program = {}};
  dx::CandidateOutcome refitted;
  refitted.refitted = true, refitted.element = "m3", refitted.fitted = "m3.k = 40 N/mm, m3.tau = 9999.93 ms";
  d.candidates.push_back(refitted);
  const std::string text = dx::diagnosis_report_text("m.rheo", d);
  CAPTURE(text);
  CHECK(text.find("  m3.tau = 9999.93 ms is at its upper bound 10000: widen it?\n") != std::string::npos);
  CHECK(text.find("s.k =") == std::string::npos);
  CHECK(text.find("m3.k =") == std::string::npos);
  const auto j = nlohmann::json::parse(dx::diagnosis_report_json("m.rheo", d, ""));
  CHECK(j.at("at_bounds") == nlohmann::json::array({"m3.tau = 9999.93 ms is at its upper bound 10000: widen it?"}));
  // The effects the data do not tell apart from the one named (Diagnosis::alike).
  CHECK(j.at("alike") == nlohmann::json::array({"amplitude-dependence"}));
  // Each refitted candidate's fitted values.
  CHECK(j.at("evidence").at("candidates").at(0).at("fitted") == "m3.k = 40 N/mm, m3.tau = 9999.93 ms");
  CHECK(j.at("evidence").at("candidates").at(0).at("at_likelihood_maximum") == false);
  // Not noise-weighted: every BIC is of its fit, none marked.
  CHECK(text.find("* BIC of the refit") == std::string::npos);
  // Noise-weighted: the model's BIC is at its likelihood's maximum, and a candidate's that is its
  // refit's (an upper bound) is marked, with the legend under the table.
  d.noise_weighted = true;
  d.candidates.front().criterion = 12120.8;
  dx::CandidateOutcome at_maximum = refitted;
  at_maximum.criterion = 1220.6, at_maximum.at_likelihood_maximum = true;
  d.candidates.push_back(at_maximum);
  const std::string weighted = dx::diagnosis_report_text("m.rheo", d);
  CAPTURE(weighted);
  CHECK(weighted.find("     12120.8*  ") != std::string::npos);
  CHECK(weighted.find("      1220.6   ") != std::string::npos);
  CHECK(weighted.find("  * BIC of the refit as it ended (by eq. 5.1), an upper bound of its value at the likelihood's maximum") != std::string::npos);
}

}  // namespace diagnosis_report_test
