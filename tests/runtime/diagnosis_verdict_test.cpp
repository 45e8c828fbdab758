// The verdict of rheo diagnose on measurements with a known truth and seeded noise (the noise of
// examples/data: stiffness x (1 + 0.01 N(0,1)), phase + 0.15 deg N(0,1); histories: force +
// 0.003 max|F| N(0,1)): `none` with the noise estimated near the injected noise where the model
// explains its data; `unexplained`, not `none`, where a systematic residual lies outside every
// candidate's reach; and the coupled bushing of issue #24 (a slider-capped Maxwell arm hidden),
// whose refit must find the arm's yield force rather than stop where the screening sized it.
#include "runtime/diagnosis/diagnose.hpp"
#include "runtime/diagnosis/diagnosis_report.hpp"

#include "diagnosis_support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>
#include <random>

using namespace rheo;
namespace dx = runtime::diagnosis;
using test::diagnose;
using test::harmonic_measurement;

namespace {

std::string summary(const dx::Diagnosis& d) {
  std::string out = fmt::format("verdict {}, gap {:.4g} -> {:.4g}, noise floor {:.4g} (+-{:.2f}), ratio {:.3g}; {}", dx::verdict_name(d),
                                d.gap_before, d.gap_after, d.noise.floor, d.noise.relative_error, d.noise_ratio, d.reason);
  for (const auto& c : d.candidates)
    out += fmt::format("\n  {:28} gain {:.3f}  {}", dx::effect_name(c.screened.effect), c.screened.gain,
                       c.refitted ? fmt::format("gap {:.4g} BIC {:.1f} in {:.1f} s", c.gap_after, c.criterion, c.wall_seconds) : "not refitted");
  return out;
}

}  // namespace

TEST_CASE("diagnose verdict, history: loops the model explains are none, the force noise found within 15 %") {
  const std::string truth = "model truth { spring s (k = 250 N/mm)  friction f (k = 300 N/mm, uy = 80 um) }";
  const std::string start =
      "model start {\n  spring s (k = 300 N/mm in [10, 10000])\n  friction f (k = 100 N/mm in [1, 10000], uy = 20 um in [0.1, 10000])\n}\n";
  const dx::Diagnosis d = diagnose(start, {test::history_measurement(truth, runtime::static_triangle({3.0, 1.0, 0.3}, 0.05, 1, 400), 22)});
  MESSAGE(summary(d));
  CHECK(d.verdict == dx::Verdict::none);
  REQUIRE(d.noise.estimated);
  CHECK(d.noise.force == doctest::Approx(0.003).epsilon(0.15));
  CHECK(std::abs(d.noise.autocorrelation) < 0.3);
}

TEST_CASE("diagnose verdict, history: a force law that is not odd, which no candidate element has, is unexplained, not none") {
  // Sine loops of a spring and a friction element with a force c u^2 (5 % of max|F| at the
  // largest displacement) on top: different in tension and compression, which every element of
  // the vocabulary (odd laws) misses.
  const std::string truth = "model truth { spring s (k = 250 N/mm)  friction f (k = 300 N/mm, uy = 80 um) }";
  const std::string start =
      "model start {\n  spring s (k = 300 N/mm in [10, 10000])\n  friction f (k = 100 N/mm in [1, 10000], uy = 20 um in [0.1, 10000])\n}\n";
  const runtime::Drive drive = runtime::quasistatic_sine({2.0, 1.0}, 0.1, 2, 400);
  runtime::FitDataSet measured = test::history_measurement(truth, drive, 23);
  auto& h = std::get<runtime::HistoryData>(measured.data);
  for (std::size_t j = 0; j < h.force.size(); ++j) h.force[j] += 0.05 * h.force_scale * std::pow(h.drive.displacement[j] / 2.0, 2);
  const dx::Diagnosis d = diagnose(start, {measured});
  MESSAGE(summary(d));
  CHECK(d.verdict == dx::Verdict::unexplained);
  CHECK(d.effect == dx::Effect::none);
  CHECK(d.added_element.empty());
  CHECK(d.noise_ratio > 3.0);
  CHECK(d.noise.force == doctest::Approx(0.003).epsilon(0.2));
  REQUIRE(d.unexplained);
  REQUIRE(d.unexplained->resembles);
  CHECK(*d.unexplained->resembles == dx::Resemblance::even_law);
  CHECK(d.reason.find("systematic") != std::string::npos);
  const auto j = nlohmann::json::parse(dx::diagnosis_report_json("start.rheo", d, ""));
  CHECK(j["effect"] == "unexplained");
  CHECK(j["unexplained"]["resembles"].get<std::string>().find("not odd") != std::string::npos);
  CHECK(dx::diagnosis_report_text("start.rheo", d).find("effect: unexplained") != std::string::npos);
  CHECK(d.refined_text.find("unexplained") != std::string::npos);
}
