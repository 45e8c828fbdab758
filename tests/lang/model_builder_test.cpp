#include "lang/frontend.hpp"

#include <doctest/doctest.h>

namespace model_builder_test {

using namespace rheo::lang;

namespace {
const Parameter* find(const CheckedModel& m, const std::string& path) {
  for (const auto& p : m.parameters)
    if (p.path == path) return &p;
  return nullptr;
}
}  // namespace

TEST_CASE("build_model: generated names, transparent unnamed blocks, named scopes") {
  Program p = compile_source("n.rheo", R"(
model m {
  param k0 = 300 N/mm in [10, 5000]
  spring (k = k0) spring spring1 (k = 1)
  parallel { maxwell (k = 1, tau = 1) }
  series fluid { friction cap (k = 2 * k0, fy = 12 N) spring (k = 1) }
})");
  const CheckedModel& m = p.models.at(0);
  CHECK(m.parameters.at(0).path == "k0");  // model-level parameters first
  CHECK(m.parameters.at(0).free);
  CHECK(m.parameters.at(0).lower == 10.0);
  CHECK(m.parameters.at(0).upper == 5000.0);
  const auto& c = m.root.children;
  REQUIRE(c.size() == 4);
  CHECK(c[0].name == "spring2");  // spring1 is taken by the explicit name after it
  CHECK(c[1].name == "spring1");
  CHECK(c[2].children.at(0).path == "maxwell1");  // unnamed block: no path prefix
  CHECK(c[3].children.at(0).path == "fluid.cap");
  CHECK(c[3].children.at(1).path == "fluid.spring1");
  REQUIRE(find(m, "fluid.cap.k"));
  CHECK(find(m, "fluid.cap.k")->value == 600.0);
  CHECK(find(m, "fluid.cap.k")->expression.evaluate({1000.0}) == 2000.0);  // re-evaluable from k0
  CHECK(find(m, "maxwell1.c")->value == 1.0);
}

TEST_CASE("build_model: instantiation flattens with prefixed paths and overrides") {
  Program p = compile_source("i.rheo", R"(
model outer { param s = 3  inner a (k0 = s * 10 N/mm, m.tau = 2 ms)  inner b () }
model inner { param k0 = 5 N/mm  maxwell m (k = k0, tau = 1 ms) }
simulate outer { step amplitude = 1 mm, duration = 1 s })");
  const CheckedModel& outer = *p.find_model("outer");
  const auto& a = outer.root.children.at(0);
  CHECK(a.kind == ElementKind::parallel);
  CHECK(a.name == "a");
  CHECK(a.path == "a");
  CHECK(a.children.at(0).path == "a.m");
  const auto& slots = a.children.at(0).parameters;
  REQUIRE(slots.size() == 2);
  CHECK(outer.parameters.at(static_cast<std::size_t>(slots[0])).path == "a.m.k");
  CHECK(outer.parameters.at(static_cast<std::size_t>(slots[0])).value == 30.0);
  CHECK(outer.parameters.at(static_cast<std::size_t>(slots[1])).value == doctest::Approx(30.0 * 0.002).scale(0.0));
  CHECK(find(outer, "b.m.k")->value == 5.0);
  CHECK(find(outer, "b.m.c")->value == doctest::Approx(0.005).scale(0.0));
}

TEST_CASE("build_model: values are checked after overrides") {
  CHECK_THROWS_WITH_AS(compile_source("o.rheo", "model o { inner x (k0 = -1) }\nmodel inner { param k0 = 5 N/mm  spring s (k = k0) }"),
                       doctest::Contains("stiffness k of spring 'x.s' must be positive, got -1 N/mm"), CompileError);
}

TEST_CASE("build_model: a parameter's value range is its own text, an override's, or none") {
  const std::string text =
      "import zener\nmodel o { inner x (k0 = 7 N/mm)  zener z (tau = 5 ms) }\nmodel inner { param k0 = 5 N/mm  maxwell m (k = k0, tau = 1 ms) }";
  Program p = compile_source("r.rheo", text);
  auto range = [&](const CheckedModel& m, const std::string& path) {
    const Parameter& q = *find(m, path);
    return q.value_begin < 0 ? std::string("none")
                             : text.substr(static_cast<std::size_t>(q.value_begin), static_cast<std::size_t>(q.value_end - q.value_begin));
  };
  const CheckedModel& o = *p.find_model("o");
  CHECK(range(o, "x.k0") == "7 N/mm");  // the override, in the user's model
  CHECK(find(o, "x.k0")->where.line == 2);
  CHECK(range(o, "x.m.tau") == "none");  // the instantiated model's default: shared by every instance
  CHECK(range(o, "x.m.c") == "none");    // generated
  CHECK(range(o, "z.tau") == "5 ms");
  CHECK(range(o, "z.k1") == "none");  // a stdlib default
  CHECK(range(*p.find_model("inner"), "m.tau") == "1 ms");
}

TEST_CASE("build_model: springpot band limits default to 0.01 Hz .. 1 kHz and can be given or overridden") {
  Program p = compile_source("s.rheo", R"(
model s { springpot sp (k = 50 N/mm, alpha = 0.3 in [0.1, 0.9], tau = 10 ms) }
model t { s inner (sp.f_high = 2 kHz) springpot own (k = 1, alpha = 0.5, tau = 1 s, f_low = 1 Hz) })");
  const CheckedModel& s = p.models.at(0);
  REQUIRE(s.root.children.at(0).parameters.size() == 5);
  CHECK(find(s, "sp.f_low")->value == 0.01);
  CHECK(find(s, "sp.f_high")->value == 1000.0);
  CHECK(find(s, "sp.f_low")->where.line == 2);  // generated at the element
  CHECK(find(s, "sp.alpha")->free);
  const CheckedModel& t = p.models.at(1);
  CHECK(find(t, "inner.sp.f_high")->value == 2000.0);
  CHECK(find(t, "own.f_low")->value == 1.0);
  CHECK(find(t, "own.f_high")->value == 1000.0);
}

TEST_CASE("build_model: a springpot's alpha lies strictly between 0 and 1, its bounds too") {
  CHECK_THROWS_WITH_AS(compile_source("a.rheo", "model a { springpot sp (k = 1, alpha = 1, tau = 1 s) }"),
                       doctest::Contains("a.rheo:1:40: error: fractional order alpha of springpot 'sp' must be below 1, got 1"), CompileError);
  CHECK_THROWS_WITH_AS(
      compile_source("a.rheo", "model a { springpot sp (k = 1, alpha = 0.5 in [0.1, 1.2], tau = 1 s) }"),
      doctest::Contains("a.rheo:1:53: error: fractional order alpha of springpot 'sp' must be below 1, so its upper bound must be too, got 1.2"),
      CompileError);
  CHECK_THROWS_WITH_AS(compile_source("a.rheo", "model a { springpot sp (k = 1, alpha = 0, tau = 1 s) }"), doctest::Contains("must be positive"),
                       CompileError);
  CHECK_THROWS_WITH_AS(compile_source("a.rheo", "model a { springpot sp (k = 1, tau = 1 s) }"),
                       doctest::Contains("springpot 'sp' is missing its fractional order alpha"), CompileError);
}

TEST_CASE("build_model: a chain of 100,000 parameter references resolves, a cycle through all of it is one error") {
  // Each parameter refers to the one declared after it: resolving p0 needs the whole chain first.
  const int n = 100000;
  std::string source = "model m {\n";
  for (int i = 0; i < n; ++i) source += "  param p" + std::to_string(i) + " = p" + std::to_string(i + 1) + "\n";
  const Program program = compile_source("chain.rheo", source + "  param p" + std::to_string(n) + " = 2 N/mm\n  spring s (k = p0)\n}\n");
  CHECK(find(program.models.at(0), "s.k")->value == 2.0);
  try {
    compile_source("cycle.rheo", source + "  param p" + std::to_string(n) + " = p0\n  spring s (k = 1 N/mm)\n}\n");
    FAIL("no error");
  } catch (const CompileError& e) {
    REQUIRE(e.diagnostics().size() == 1);
    CHECK(e.diagnostics()[0].where.line == 2);
    CHECK(e.diagnostics()[0].message.find("reference cycle: p0 -> p1 -> p2") == 0);
    CHECK(e.diagnostics()[0].message.find("p14 -> ... (99972 more) -> p99987 -> ") != std::string::npos);
    CHECK(e.diagnostics()[0].message.find("-> p100000 -> p0; a parameter cannot depend on itself") != std::string::npos);
  }
}

}  // namespace model_builder_test
