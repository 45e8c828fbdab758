// The reports of `rheo fit` (runtime/fit/fit_report.hpp): the JSON summary has every documented
// field, with parameter values, bounds and standard errors in the unit the model wrote; the
// text report lists every free parameter with its unit and flags values at a bound.
#include "runtime/fit/fit_report.hpp"
#include "runtime/protocols/run_history.hpp"
#include "runtime/protocols/harmonic.hpp"

#include "support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace fit_report_test {

using namespace rheo;
using nlohmann::json;

namespace {

// tau written in ms, uy in um, the spring's k without a unit (internal N/mm); the spring's upper
// bound (250) lies below the true value (300), so the fit ends on it.
constexpr const char* start_source = R"(model r {
  spring   e (k = 200 in [10, 250])
  maxwell  m (k = 30 N/mm in [1, 1000], tau = 8 ms in [0.1, 100])
  friction f (k = 120 N/mm in [1, 5000], uy = 25 um in [1, 1000])
})";

runtime::FitDataSet harmonic_from(const runtime::Network& truth) {
  runtime::HarmonicData d;
  d.path = "grid.csv";
  for (double u0 : {0.01, 0.05, 0.2, 1.0})
    for (double f : {1.0, 10.0, 40.0}) {
      const auto p = runtime::simulate_harmonic_point(truth, u0, f, {});
      d.amplitude.push_back(u0), d.frequency.push_back(f);
      d.stiffness.push_back(p.measures.stiffness), d.phase.push_back(p.measures.phase);
      d.rows.push_back(static_cast<int>(d.rows.size()) + 3);
    }
  return {"grid.csv", 1.0, d};
}

struct Fitted {
  runtime::FitDescription description{"r.rheo", "exact", "phi", "default", 3};
  runtime::FitResult result;
};

Fitted fitted(bool interrupt_first) {
  const auto truth = test::network_from("model r { spring e (k = 300) maxwell m (k = 60, tau = 5 ms) friction f (k = 200, uy = 40 um) }", "r");
  const auto start = test::network_from(start_source, "r");
  runtime::FitSettings settings;
  settings.search.max_evaluations = 400;
  settings.search.seed = 3;
  const std::atomic<bool> stop{interrupt_first};
  settings.interrupt = &stop;
  Fitted f;
  f.result = runtime::fit(start, runtime::bounded_parameters(start),
                          {harmonic_from(truth), test::history_data_of(truth, runtime::static_triangle({0.5, 0.1}, 0.5, 1, 100), "loop.csv", 0.5)},
                          settings);
  return f;
}

int index_of(const runtime::FitResult& r, const std::string& path) {
  const auto& parameters = r.network.model().parameters;
  for (std::size_t i = 0; i < parameters.size(); ++i)
    if (parameters[i].path == path) return static_cast<int>(i);
  FAIL("no parameter " << path);
  return -1;
}

const json& parameter_entry(const json& j, const std::string& path) {
  for (const json& p : j.at("parameters"))
    if (p.at("path") == path) return p;
  FAIL("no JSON entry for " << path);
  return j;
}

}  // namespace

TEST_CASE("in_written_unit converts internal values to the unit written, and keeps unitless ones") {
  const auto model = test::model_from("model u { maxwell m (k = 2 kN/mm, tau = 5 ms) friction f (k = 100, uy = 40 um) }", "u");
  for (const auto& p : model.parameters) {
    CAPTURE(p.path);
    if (p.path == "m.k") CHECK(runtime::in_written_unit(p, p.value) == doctest::Approx(2.0).epsilon(1e-15));
    if (p.path == "m.tau") CHECK(runtime::in_written_unit(p, p.value) == doctest::Approx(5.0).epsilon(1e-15));
    if (p.path == "f.uy") CHECK(runtime::in_written_unit(p, p.value) == doctest::Approx(40.0).epsilon(1e-15));
    if (p.path == "f.k") {
      CHECK(runtime::in_written_unit(p, p.value) == 100.0);
      CHECK(runtime::written_unit(p) == "N/mm");  // the internal unit of a stiffness
    }
  }
}

TEST_CASE("the JSON summary has the documented fields, parameters in the units the model wrote") {
  const Fitted f = fitted(false);
  const runtime::FitResult& r = f.result;
  const json j = json::parse(runtime::fit_report_json(f.description, r));
  for (const char* key : {"model", "source", "method", "objective", "optimizer", "seed", "status", "interrupted", "evaluations",
                          "non_finite_evaluations", "wall_seconds", "phi", "err", "notes", "parameters", "correlation", "data"})
    CHECK_MESSAGE(j.contains(key), key);
  CHECK(j["model"] == "r");
  CHECK(j["source"] == "r.rheo");
  CHECK(j["seed"] == 3);
  CHECK(j["interrupted"] == false);
  CHECK(j["evaluations"] == r.evaluations);
  CHECK(j["err"].get<double>() == r.err);
  CHECK(j["phi"].get<double>() == r.phi);

  REQUIRE(j["parameters"].size() == r.network.model().parameters.size());
  struct Expect {
    const char* path;
    const char* unit;
    double scale;  // internal value / written value
    double start, lower, upper;
  };
  for (const Expect& e : {Expect{"e.k", "N/mm", 1.0, 200, 10, 250}, Expect{"m.tau", "ms", 1e-3, 8, 0.1, 100},
                          Expect{"f.uy", "um", 1e-3, 25, 1, 1000}, Expect{"f.k", "N/mm", 1.0, 120, 1, 5000}}) {
    CAPTURE(e.path);
    const json& p = parameter_entry(j, e.path);
    const int i = index_of(r, e.path);
    const auto k = static_cast<std::size_t>(std::find(r.free.begin(), r.free.end(), i) - r.free.begin());
    REQUIRE(k < r.free.size());
    CHECK(p["unit"] == e.unit);
    CHECK(p["free"] == true);
    CHECK(p["start"].get<double>() == doctest::Approx(e.start).epsilon(1e-14).scale(0.0));
    CHECK(p["lower"].get<double>() == doctest::Approx(e.lower).epsilon(1e-14).scale(0.0));
    CHECK(p["upper"].get<double>() == doctest::Approx(e.upper).epsilon(1e-14).scale(0.0));
    CHECK(p["value"].get<double>() == doctest::Approx(r.network.parameter(i) / e.scale).epsilon(1e-14).scale(0.0));
    REQUIRE(p.contains("identifiable"));
    if (p["identifiable"] == true) {
      REQUIRE(p.contains("standard_error"));
      CHECK(p["standard_error"].get<double>() == doctest::Approx(r.statistics.standard_error[k] / e.scale).epsilon(1e-14).scale(0.0));
    }
  }
  // The fit found the truth where the bounds allow it (tau = 5 ms, uy = 40 um) and e.k on its bound.
  CHECK(parameter_entry(j, "e.k")["value"].get<double>() == doctest::Approx(250.0).epsilon(1e-6));
  // A computed parameter (the Maxwell element's c = k tau) is reported but not free, without bounds.
  const json& c = parameter_entry(j, "m.c");
  CHECK(c["free"] == false);
  CHECK_FALSE(c.contains("lower"));
  CHECK_FALSE(c.contains("standard_error"));

  const json& correlation = j["correlation"];
  REQUIRE(correlation["parameters"].size() == r.free.size());
  REQUIRE(correlation["matrix"].size() == r.free.size());
  for (std::size_t a = 0; a < r.free.size(); ++a) {
    CHECK(correlation["parameters"][a] == r.network.model().parameters[static_cast<std::size_t>(r.free[a])].path);
    CHECK(correlation["matrix"][a].size() == r.free.size());
  }

  REQUIRE(j["data"].size() == 2);
  const json& grid = j["data"][0];
  CHECK(grid["file"] == "grid.csv");
  CHECK(grid["kind"] == "harmonic");
  CHECK(grid["points"] == 12);
  CHECK(grid["weight"] == 1.0);
  CHECK(grid.contains("phi"));
  REQUIRE(grid["residuals"].size() == 12);
  const json& point = grid["residuals"][11];
  for (const char* key : {"amplitude_mm", "frequency_hz", "stiffness_measured", "stiffness_model", "phase_measured_deg", "phase_model_deg",
                          "stiffness_residual", "damping_residual"})
    CHECK_MESSAGE(point.contains(key), key);
  CHECK(point["amplitude_mm"] == 1.0);
  CHECK(point["frequency_hz"] == 40.0);
  const double measured_deg = r.datasets[0].measured_phase[11] * 180.0 / std::numbers::pi;
  CHECK(point["phase_measured_deg"].get<double>() == doctest::Approx(measured_deg).epsilon(1e-14));
  CHECK(point["stiffness_residual"].get<double>() ==
        doctest::Approx(point["stiffness_model"].get<double>() / point["stiffness_measured"].get<double>() - 1.0).epsilon(1e-9).scale(0.0));
  const json& loop = j["data"][1];
  CHECK(loop["kind"] == "history");
  CHECK(loop["weight"] == 0.5);
  CHECK(loop["points"] == r.datasets[1].prediction.force.size());
  CHECK(loop["residuals"]["rms"].get<double>() == r.datasets[1].err);
  CHECK(loop["residuals"]["max"].get<double>() == r.datasets[1].worst);
  CHECK_FALSE(loop.contains("phi"));
}

TEST_CASE("the text report lists every free parameter with its unit, the data and the error measures") {
  const Fitted f = fitted(false);
  const std::string text = runtime::fit_report_text(f.description, f.result);
  CAPTURE(text);
  CHECK(text.find("rheo fit: model r from r.rheo") != std::string::npos);
  CHECK(text.find("data grid.csv (harmonic, 12 points, weight 1)") != std::string::npos);
  CHECK(text.find("data loop.csv (history, ") != std::string::npos);
  CHECK(text.find("method exact, objective phi, optimizer default, seed 3") != std::string::npos);
  for (const auto& row : {std::pair{"e.k", "N/mm"}, {"m.k", "N/mm"}, {"m.tau", "ms"}, {"f.k", "N/mm"}, {"f.uy", "um"}}) {
    const char* const path = row.first;  // not a structured binding: Clang 14 cannot capture one
    const char* const unit = row.second;
    CAPTURE(path);
    const auto line_start = text.find(std::string("\n  ") + path + " ");
    REQUIRE(line_start != std::string::npos);
    const std::string line = text.substr(line_start + 1, text.find('\n', line_start + 1) - line_start - 1);
    CHECK(line.find(std::string("  ") + unit + " ") != std::string::npos);
    CHECK((line.find("at a bound") != std::string::npos) == (std::string(path) == "e.k"));
  }
  CHECK(text.find("m.c") == std::string::npos);  // not free: not listed
  CHECK(text.find("grid.csv: phi (5.1) = ") != std::string::npos);
  CHECK(text.find("loop.csv: force residual RMS") != std::string::npos);
  CHECK(text.find("optimizer status") != std::string::npos);
}

TEST_CASE("an interrupted fit says so in both reports and has no standard errors") {
  const Fitted f = fitted(true);
  CHECK(f.result.interrupted);
  const std::string text = runtime::fit_report_text(f.description, f.result);
  CHECK(text.find("interrupted: these are the best values found so far") != std::string::npos);
  const json j = json::parse(runtime::fit_report_json(f.description, f.result));
  CHECK(j["interrupted"] == true);
  CHECK(j["status"] == "interrupted");
  for (const json& p : j["parameters"]) CHECK_FALSE(p.contains("standard_error"));
}

TEST_CASE("a value the search left just short of a bound is at it: flagged in the table, the notes and the JSON") {
  Fitted f = fitted(false);
  // m.tau 1e-6 short of its upper bound of 100 ms, as a local search stopping at its tolerance leaves it.
  std::vector<double> values = f.result.network.parameters();
  const auto tau = static_cast<std::size_t>(index_of(f.result, "m.tau"));
  values[tau] = 0.1 * (1.0 - 1e-6);
  f.result.network = f.result.network.with_parameters(values);
  const std::string text = runtime::fit_report_text(f.description, f.result);
  CAPTURE(text);
  const auto line_start = text.find("\n  m.tau ");
  REQUIRE(line_start != std::string::npos);
  CHECK(text.substr(line_start, text.find('\n', line_start + 1) - line_start).find("at a bound: widen it?") != std::string::npos);
  const auto notes = runtime::bound_notes(f.result);
  REQUIRE(notes.size() == 2);  // e.k, fitted onto its upper bound, and m.tau
  CHECK(notes[0].starts_with("e.k = 250 N/mm is at its upper bound 250"));
  CHECK(notes[1] == "m.tau = 99.9999 ms is at its upper bound 100: widen it?");
  const json j = json::parse(runtime::fit_report_json(f.description, f.result));
  CHECK(parameter_entry(j, "m.tau").at("at_bound") == "upper");
  CHECK_FALSE(parameter_entry(j, "m.k").contains("at_bound"));
}

TEST_CASE("the start column shows the start the search used: the yeoh start's, marked so") {
  const auto truth = test::network_from("model y { yeoh r (D10 = 389.4253, D20 = -2.1094, D30 = 0.0786) maxwell m (k = 60, tau = 5 ms) }", "y");
  const auto start = test::network_from(
      "model y { yeoh r (D10 = 300 in [10, 5000], D20 = 0 in [-50, 50], D30 = 0 in [-5, 5])\n"
      " maxwell m (k = 100 in [1, 1000], tau = 10 ms in [0.1, 100]) }",
      "y");
  runtime::FitSettings settings;
  settings.search.max_evaluations = 5;
  settings.statistics = false;
  Fitted f;
  f.result = runtime::fit(start, runtime::bounded_parameters(start),
                          {test::history_data_of(truth, runtime::static_triangle({6.25, 3.0}, 0.5, 1, 200), "loop.csv")}, settings);
  const runtime::FitResult& r = f.result;
  const auto d10 = static_cast<std::size_t>(index_of(r, "r.D10"));
  CHECK(r.yeoh_started.size() == 3);
  const double started = r.start_values.at(d10);
  CHECK(started != 300.0);  // the mean curve's, not the model's
  const std::string note = fmt::format("start r.D10 = {:.6g} N/mm from the mean curve of loop.csv", started);
  CHECK(std::any_of(r.notes.begin(), r.notes.end(), [&](const std::string& n) { return n.starts_with(note); }));
  const std::string text = runtime::fit_report_text(f.description, r);
  CAPTURE(text);
  const auto line_of = [&](const std::string& path) {
    const auto at = text.find("\n  " + path + " ");
    REQUIRE(at != std::string::npos);
    return text.substr(at + 1, text.find('\n', at + 1) - at - 1);
  };
  const std::string row = line_of("r.D10");
  CHECK(row.find(fmt::format("  {:.6g}  ", started)) != std::string::npos);
  CHECK(row.find("start: yeoh mean curve") != std::string::npos);
  CHECK(line_of("m.k").find("start: yeoh") == std::string::npos);
  CHECK(line_of("m.k").find("  100  ") != std::string::npos);
  const json j = json::parse(runtime::fit_report_json(f.description, r));
  CHECK(parameter_entry(j, "r.D10").at("start").get<double>() == started);
  CHECK(parameter_entry(j, "r.D10").at("start_from") == "yeoh");
  CHECK(parameter_entry(j, "m.k").at("start_from") == "given");
}

TEST_CASE("two stiffnesses in series are not identifiable, and the report names the combination the data fix") {
  // #22 item 7: only k1 k2/(k1 + k2) acts; the fit must say so rather than print a standard
  // error of millions of percent with r = +-1.
  const char* source = R"(model s {
  series c { spring k1 (k = 300 N/mm in [1, 10000])  spring k2 (k = 100 N/mm in [1, 10000]) }
  maxwell m (k = 50 N/mm, tau = 10 ms in [0.1, 1000])
})";
  const auto truth = test::network_from(
      "model s { series c { spring k1 (k = 200 N/mm)  spring k2 (k = 200 N/mm) }\n"
      " maxwell m (k = 50 N/mm, tau = 10 ms) }",
      "s");
  const auto start = test::network_from(source, "s");
  runtime::FitSettings settings;
  const runtime::FitResult r = runtime::fit(start, runtime::bounded_parameters(start), {harmonic_from(truth)}, settings);
  REQUIRE(r.statistics.identifiable.size() == 3);
  CHECK_FALSE(r.statistics.identifiable[0]);
  CHECK_FALSE(r.statistics.identifiable[1]);
  CHECK(r.statistics.identifiable[2]);  // tau is determined
  REQUIRE(r.statistics.together.size() == 1);
  CHECK(r.statistics.together.front() == std::vector<int>{0, 1});
  // The combination is the truth's 100 N/mm.
  const double k1 = r.network.parameter(r.free[0]), k2 = r.network.parameter(r.free[1]);
  CHECK(k1 * k2 / (k1 + k2) == doctest::Approx(100.0).epsilon(1e-6));
  const std::string text = runtime::fit_report_text({}, r);
  CHECK(text.find("not identifiable: c.k1.k and c.k2.k act only together") != std::string::npos);
  CHECK(text.find("in series: only k1 k2/(k1 + k2)") != std::string::npos);
  CHECK(text.find("strongly correlated: c.k1.k") == std::string::npos);
  const json j = json::parse(runtime::fit_report_json({}, r));
  CHECK(j["not_identifiable_together"] == json::array({json::array({"c.k1.k", "c.k2.k"})}));
}

}  // namespace fit_report_test
