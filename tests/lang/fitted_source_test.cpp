#include "lang/fitted_source.hpp"

#include "lang/frontend.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fitted_source_test {

using namespace rheo::lang;

namespace {

const char* kSource = R"(# Bushing for the writer test: comments, bounds and units stay as written.
import zener

model bushing {
  param k0 = 300 in [10, 5000]           # a plain number: a factor
  param w = 62.8 rad/s in [1, 1000]      # angular frequency: 1 rad/s = 1/(2 pi) Hz
  param phase = 30 deg in [1, 89]
  param k2 = 2 * 50 N/mm in [1, 1000]    # a constant expression without a literal unit
  yeoh     rubber (D10 = 389.43 N/mm in [100, 1000], D20 = -2.1094 N/mm^3 in [-10, 10], D30 = 0.0786 N/mm^5)
  maxwell  m1     (k = 61.476 kN/m in [1, 1000], tau = 4.335 ms in [0.1, 100])   # kN/m = N/mm
  friction f1     (k = 1016.6 N/mm, uy = 101.58 um in [1, 1000])
  zener    z      (k_inf = 90 N/mm in [10, 500], tau = 20 ms)
  spring   s      (k = k0 * 1 N/mm)
  dashpot  d      (c = 2 in [0.1, 10])   # a plain number: internal N*s/mm
}
simulate { harmonic frequency = 10 Hz, amplitude = 1 mm }
)";

const CheckedModel& model_of(const Program& p) { return *p.find_model("bushing"); }

int index_of(const CheckedModel& m, const std::string& path) {
  for (std::size_t i = 0; i < m.parameters.size(); ++i)
    if (m.parameters[i].path == path) return static_cast<int>(i);
  FAIL("no parameter " << path);
  return -1;
}

// The parameters whose value is written for them in the file (the ones a fit may change).
std::vector<int> written(const CheckedModel& m) {
  std::vector<int> out;
  for (std::size_t i = 0; i < m.parameters.size(); ++i)
    if (m.parameters[i].value_begin >= 0 && m.parameters[i].expression.is_constant()) out.push_back(static_cast<int>(i));
  return out;
}

}  // namespace

TEST_CASE("write_fitted_source: changed values round-trip to 1e-12, everything else is kept byte for byte") {
  const std::string source = kSource;
  const Program before = compile_source("f.rheo", source);
  const CheckedModel& m = model_of(before);
  const std::vector<int> changed = written(m);
  std::vector<std::string> expected_changed{"k0",   "w",      "phase", "k2",    "rubber.D10", "rubber.D20", "rubber.D30",
                                            "m1.k", "m1.tau", "f1.k",  "f1.uy", "z.k_inf",    "z.tau",      "d.c"};
  std::vector<std::string> names;
  for (int i : changed) names.push_back(m.parameters[static_cast<std::size_t>(i)].path);
  CHECK(names == expected_changed);

  std::vector<double> values;
  for (const auto& p : m.parameters) values.push_back(p.value);
  for (int i : changed) values[static_cast<std::size_t>(i)] *= 1.0123456789012345;
  const std::vector<std::string> header{"fitted by rheo fit", "phi = 0.0123"};
  const std::string out = write_fitted_source(source, "f.rheo", m, values, changed, header);
  REQUIRE(out.rfind("# fitted by rheo fit\n# phi = 0.0123\n", 0) == 0);

  const Program after = compile_source("f.rheo", out);
  const CheckedModel& n = model_of(after);
  REQUIRE(n.parameters.size() == m.parameters.size());
  for (int i : changed) {
    const auto& p = n.parameters[static_cast<std::size_t>(i)];
    CAPTURE(p.path);
    CHECK(std::abs(p.value - values[static_cast<std::size_t>(i)]) <= 1e-12 * std::abs(values[static_cast<std::size_t>(i)]));
    CHECK(p.unit == (p.path == "k2" ? "N/mm" : p.path == "d.c" ? "N*s/mm" : m.parameters[static_cast<std::size_t>(i)].unit));
    CHECK(p.free == m.parameters[static_cast<std::size_t>(i)].free);  // bounds kept, in the same unit
    CHECK(p.lower == doctest::Approx(m.parameters[static_cast<std::size_t>(i)].lower).epsilon(1e-15));
  }
  // Derived parameters follow their inputs.
  const auto& c = n.parameters[static_cast<std::size_t>(index_of(n, "m1.c"))];
  CHECK(c.value ==
        doctest::Approx(values[static_cast<std::size_t>(index_of(m, "m1.k"))] * values[static_cast<std::size_t>(index_of(m, "m1.tau"))]).scale(0.0));
  CHECK(n.parameters[static_cast<std::size_t>(index_of(n, "s.k"))].value == doctest::Approx(values[static_cast<std::size_t>(index_of(m, "k0"))]));

  // The text between the value expressions is unchanged: compare the gaps of the old and new text.
  const std::size_t shift = std::string("# fitted by rheo fit\n# phi = 0.0123\n").size();
  std::vector<std::pair<std::size_t, std::size_t>> old_ranges, new_ranges;
  for (int i : changed) {
    const auto& old_p = m.parameters[static_cast<std::size_t>(i)];
    const auto& new_p = n.parameters[static_cast<std::size_t>(i)];
    old_ranges.emplace_back(old_p.value_begin, old_p.value_end);
    new_ranges.emplace_back(static_cast<std::size_t>(new_p.value_begin) - shift, static_cast<std::size_t>(new_p.value_end) - shift);
  }
  std::sort(old_ranges.begin(), old_ranges.end());
  std::sort(new_ranges.begin(), new_ranges.end());
  const std::string body = out.substr(shift);
  std::size_t old_at = 0, new_at = 0;
  for (std::size_t r = 0; r <= old_ranges.size(); ++r) {
    const std::size_t old_end = r < old_ranges.size() ? old_ranges[r].first : source.size();
    const std::size_t new_end = r < new_ranges.size() ? new_ranges[r].first : body.size();
    CHECK(source.substr(old_at, old_end - old_at) == body.substr(new_at, new_end - new_at));
    if (r < old_ranges.size()) old_at = old_ranges[r].second, new_at = new_ranges[r].second;
  }
  CHECK(body.find("# a plain number: internal N*s/mm") != std::string::npos);
  CHECK(body.find("in [0.1, 100])   # kN/m = N/mm") != std::string::npos);
}

TEST_CASE("write_fitted_source: nothing changed and no header gives the source back") {
  const Program p = compile_source("f.rheo", kSource);
  std::vector<double> values;
  for (const auto& q : model_of(p).parameters) values.push_back(q.value);
  CHECK(write_fitted_source(kSource, "f.rheo", model_of(p), values, {}, {}) == kSource);
  CHECK(write_fitted_source(kSource, "f.rheo", model_of(p), values, {}, {"a\nb", ""}) == std::string("# a\n# b\n#\n") + kSource);
}

TEST_CASE("write_fitted_source: values not written in the file are errors that say to override them") {
  const Program p = compile_source("f.rheo", kSource);
  const CheckedModel& m = model_of(p);
  std::vector<double> values;
  for (const auto& q : m.parameters) values.push_back(q.value);
  try {
    write_fitted_source(kSource, "f.rheo", m, values, {index_of(m, "z.k1"), index_of(m, "m1.c")}, {});
    FAIL("expected a CompileError");
  } catch (const CompileError& e) {
    REQUIRE(e.diagnostics().size() == 2);
    const std::string text = e.what();
    CHECK(text.find("<stdlib>/zener.rheo:5:14: error: the value of 'z.k1' is not written for it in f.rheo") != std::string::npos);
    CHECK(text.find("override it where the model is instantiated, e.g. `k1 = ... in [LO, HI]`") != std::string::npos);
    CHECK(text.find("param k1 = 50 N/mm\n") != std::string::npos);  // the stdlib line is quoted
    CHECK(text.find("'m1.c' is computed from other parameters") != std::string::npos);
  }
  CHECK_THROWS_AS(write_fitted_source(kSource, "f.rheo", m, {1.0}, {}, {}), std::logic_error);
  CHECK_THROWS_AS(write_fitted_source(kSource, "f.rheo", m, values, {static_cast<int>(values.size())}, {}), std::logic_error);
  values[static_cast<std::size_t>(index_of(m, "k0"))] = std::nan("");
  CHECK_THROWS_AS(write_fitted_source(kSource, "f.rheo", m, values, {index_of(m, "k0")}, {}), std::logic_error);
  CHECK_THROWS_AS(write_fitted_source("model bushing {}", "f.rheo", m, values, {index_of(m, "m1.k")}, {}), std::logic_error);
}

TEST_CASE("format_parameter_value: the parameter's unit, at least 10 digits, the shortest that round-trips") {
  Parameter p;
  p.dimension = dim::length;
  p.unit = "um";
  CHECK(format_parameter_value(p, 0.10158) == "101.58 um");
  CHECK(format_parameter_value(p, 1.0 / 3.0) == "333.3333333333 um");
  p.unit = "";
  CHECK(format_parameter_value(p, 2.5) == "2.5 mm");
  p.dimension = dim::frequency;
  CHECK(format_parameter_value(p, 2.5) == "2.5 Hz");
  p.dimension = dim::none;
  CHECK(format_parameter_value(p, 1e-20) == "1e-20");
  p.dimension = {0, -1, 0};
  CHECK(format_parameter_value(p, 0.5) == "0.5 / 1 mm");
}

TEST_CASE("write_fitted_source: a data line's fitted setting replaces its value, parameters as before") {
  const std::string text = "model s {\n  spring e (k = 10 N/mm in [1, 1000])\n}\nfit {\n  data \"rig.csv\", force_offset = free  # zero\n}\n";
  const Program p = compile_source("s.rheo", text);
  const CheckedModel& m = p.models.at(0);
  const ForceOffsetSetting& offset = p.fits.at(0).data.at(0).force_offset;
  const std::string out = write_fitted_source(text, "s.rheo", m, {80.0}, {0}, {}, {{offset.value_begin, offset.value_end, "40.5 N"}});
  CHECK(out == "model s {\n  spring e (k = 80 N/mm in [1, 1000])\n}\nfit {\n  data \"rig.csv\", force_offset = 40.5 N  # zero\n}\n");
  const Program again = compile_source("s.rheo", out);
  CHECK(again.fits.at(0).data.at(0).force_offset.value == 40.5);
  CHECK_THROWS_AS(write_fitted_source(text, "s.rheo", m, {80.0}, {0}, {}, {{-1, 3, "1 N"}}), std::logic_error);
}

TEST_CASE("write_fitted_source: one-sided yield forces, a gap's center and poly_spring coefficients are written back like others") {
  const std::string source = R"(model rig {
  friction f (k = 2 N/mm, fy_pos = 13 kN in [1, 50], fy_neg = 20 kN in [1, 50])
  series b { gap g (width = 1 mm in [0.1, 5], center = 0.2 mm in [-1, 1])  poly_spring p (k1 = 10 N/mm in [1, 100], k2 = -0.5 N/mm^2 in [-5, 5]) }
}
)";
  const Program program = compile_source("rig.rheo", source);
  const CheckedModel& m = *program.find_model("rig");
  std::vector<double> values;
  for (const auto& p : m.parameters) values.push_back(p.value);
  std::vector<int> changed;
  for (const char* path : {"f.fy_pos", "f.fy_neg", "b.g.center", "b.p.k2"}) changed.push_back(index_of(m, path));
  values[static_cast<std::size_t>(changed[0])] = 12500.0, values[static_cast<std::size_t>(changed[1])] = 21000.0;
  values[static_cast<std::size_t>(changed[2])] = -0.15, values[static_cast<std::size_t>(changed[3])] = 0.75;
  const std::string written = write_fitted_source(source, "rig.rheo", m, values, changed, {});
  CHECK(written.find("fy_pos = 12.5 kN in [1, 50]") != std::string::npos);
  CHECK(written.find("fy_neg = 21 kN in [1, 50]") != std::string::npos);
  CHECK(written.find("center = -0.15 mm in [-1, 1]") != std::string::npos);
  CHECK(written.find("k2 = 0.75 N/mm^2 in [-5, 5]") != std::string::npos);
  const Program again = compile_source("rig.rheo", written);
  CHECK(again.find_model("rig")->parameters[static_cast<std::size_t>(changed[1])].value == doctest::Approx(21000.0));
}

}  // namespace fitted_source_test
