#include "lang/parser.hpp"

#include "lang/limits.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

namespace parser_test {

using namespace rheo::lang;

namespace {
std::string parse_error(std::string_view text) {
  try {
    parse("p.rheo", text);
  } catch (const CompileError& e) {
    REQUIRE(e.diagnostics().size() == 1);
    return e.what();
  }
  return "no error";
}
}  // namespace

TEST_CASE("parse: statements are free-form, units bind to the number before them") {
  ast::File f = parse("p.rheo",
                      "import zener model m { param k0 = 300 N/mm in [10, 5000] maxwell m1 (k = 2 * k0, tau = 4.335ms)\n"
                      "series s { spring (k=.5) } } simulate m { step amplitude = 1 in, duration = 4. s output \"o.csv\" }");
  REQUIRE(f.imports.size() == 1);
  REQUIRE(f.models.size() == 1);
  const auto& m = f.models[0];
  REQUIRE(m.parameters.size() == 1);
  CHECK(m.parameters[0].value->unit == "N/mm");
  CHECK(m.parameters[0].bounds.has_value());
  REQUIRE(m.elements.size() == 2);
  const auto& m1 = m.elements[0];
  CHECK(m1.kind == "maxwell");
  CHECK(m1.name == "m1");
  REQUIRE(m1.arguments.size() == 2);
  CHECK(m1.arguments[0].value->kind == ast::Expr::Kind::multiply);
  CHECK(m1.arguments[0].value->rhs->path == "k0");
  CHECK(m1.arguments[1].value->unit == "ms");
  CHECK(m.elements[1].block);
  CHECK(m.elements[1].children.at(0).arguments.at(0).value->number == 0.5);
  const auto& sim = f.simulations.at(0);
  CHECK(sim.model == "m");
  REQUIRE(sim.lines.size() == 2);
  CHECK(sim.lines[0].kind == "step");
  CHECK(sim.lines[0].settings.at(0).value.items.at(0)->unit == "in");  // inch, not bounds
  CHECK(sim.lines[1].output);
  CHECK(sim.lines[1].file == "o.csv");
}

TEST_CASE("parse: precedence, unary minus, ranges and lists") {
  ast::File f = parse("p.rheo", "simulate { h a = -1 + 2 * 3 N, b = 1..5 step 1, c = [1, 2 mm] um, d = \"x\" }");
  const auto& s = f.simulations.at(0).lines.at(0).settings;
  REQUIRE(s.size() == 4);
  const auto& a = *s[0].value.items.at(0);
  CHECK(a.kind == ast::Expr::Kind::add);
  CHECK(a.lhs->kind == ast::Expr::Kind::negate);
  CHECK(a.rhs->kind == ast::Expr::Kind::multiply);
  CHECK(a.rhs->rhs->unit == "N");
  CHECK(s[1].value.kind == ast::SettingValue::Kind::range);
  CHECK(s[1].value.items.size() == 3);
  CHECK(s[2].value.kind == ast::SettingValue::Kind::list);
  CHECK(s[2].value.unit == "um");
  CHECK(s[2].value.items[1]->unit == "mm");
  CHECK(s[3].value.text == "x");
}

TEST_CASE("parse: errors name the rule that failed, with position and caret") {
  CHECK(parse_error("model m {\n  maxwell m1 (k = 1 N/mm, tau = 2 ms\n}\n")
            .find("p.rheo:3:1: error: expected ')' to close the argument list of 'maxwell m1', found '}'\n  }\n  ^\n") != std::string::npos);
  CHECK(parse_error("model m { spring s k = 1 }").find("1:20: error: expected '(' to open the argument list of 'spring s'") != std::string::npos);
  CHECK(parse_error("model { }").find("expected a model name after 'model'") != std::string::npos);
  CHECK(parse_error("model m { spring (k = 1 in [1 2]) }").find("expected ',' between the lower and upper bound") != std::string::npos);
  CHECK(parse_error("simulate { h f = 1 .. 2 }").find("expected 'step' after the end of the range") != std::string::npos);
  CHECK(parse_error("simulate { h f = [1, 2 }").find("expected ',' or ']' to close the list") != std::string::npos);
  CHECK(parse_error("simulate { output \"a\nb\" }").find("unterminated string literal") != std::string::npos);
  CHECK(parse_error("model m { spring (k = (1 + 2 }").find("expected ')' to close the parenthesized expression") != std::string::npos);
}

TEST_CASE("parse_setting_text: one setting and nothing after it") {
  auto s = parse_setting_text("<command line>", "  amplitude = [1, 2] mm ");
  CHECK(s.key == "amplitude");
  CHECK(s.value.items.size() == 2);
  CHECK_THROWS_AS(parse_setting_text("<command line>", "amplitude = 1 mm, x = 2"), CompileError);
}

TEST_CASE("parse_data_text: a file name to the first comma or in double quotes, then a data line's settings") {
  auto line = parse_data_text("<command line>", "  sweep data.txt , step = \"Amplitude sweep\", area = 314 mm^2");
  CHECK(line.kind == ast::FitLine::Kind::data);
  CHECK(line.file == "sweep data.txt");  // blanks around the name dropped, inside kept
  CHECK(line.file_where.column == 3);
  REQUIRE(line.settings.size() == 2);
  CHECK(line.settings[0].key == "step");  // a keyword elsewhere, a key here
  CHECK(line.settings[0].value.text == "Amplitude sweep");
  CHECK(line.settings[1].key == "area");
  CHECK(line.settings[1].where.column == 46);
  auto quoted = parse_data_text("<command line>", R"("run 3, cured.csv", weight = 0.5)");
  CHECK(quoted.file == "run 3, cured.csv");
  REQUIRE(quoted.settings.size() == 1);
  CHECK(quoted.settings[0].key == "weight");
  CHECK(parse_data_text("<command line>", R"("a,b.csv")").settings.empty());
  CHECK_THROWS_WITH_AS(parse_data_text("<command line>", "a.csv, weight"), doctest::Contains("1:14: error: expected '=' after the setting name"),
                       CompileError);
  CHECK_THROWS_WITH_AS(parse_data_text("<command line>", "a.csv,"), doctest::Contains("expected a setting `KEY = VALUE`, found end of file"),
                       CompileError);
  CHECK_THROWS_WITH_AS(parse_data_text("<command line>", R"("a,b.csv" x)"),
                       doctest::Contains("1:11: error: expected ', KEY = VALUE' (a data line's setting) or the end"), CompileError);
  CHECK_THROWS_WITH_AS(parse_data_text("<command line>", R"("a,b.csv)"), doctest::Contains("unterminated string literal"), CompileError);
}

TEST_CASE("parse: fit blocks are data lines, output lines and settings lines, `data` is reserved only there") {
  ast::File f = parse("p.rheo", R"(model data { spring data (k = 1) }
fit data {
  data "a.csv"  data "b.csv", weight = 0.5
  objective = phi, stiffness_weight = 0.5
  free = [m1.k, m1.tau]
  output "fitted.rheo"
}
fit {})");
  REQUIRE(f.fits.size() == 2);
  const auto& fit = f.fits[0];
  CHECK(fit.model == "data");
  CHECK(fit.model_where.column == 5);
  REQUIRE(fit.lines.size() == 5);
  CHECK(fit.lines[0].kind == ast::FitLine::Kind::data);
  CHECK(fit.lines[0].file == "a.csv");
  CHECK(fit.lines[0].settings.empty());
  CHECK(fit.lines[1].file == "b.csv");
  CHECK(fit.lines[1].file_where.column == 22);
  REQUIRE(fit.lines[1].settings.size() == 1);
  CHECK(fit.lines[1].settings[0].key == "weight");
  CHECK(fit.lines[2].kind == ast::FitLine::Kind::settings);
  CHECK(fit.lines[2].where.line == 4);
  REQUIRE(fit.lines[2].settings.size() == 2);
  CHECK(fit.lines[2].settings[1].key == "stiffness_weight");
  CHECK(fit.lines[3].settings.at(0).value.items.at(1)->path == "m1.tau");
  CHECK(fit.lines[4].kind == ast::FitLine::Kind::output);
  CHECK(fit.lines[4].file == "fitted.rheo");
  CHECK(f.fits[1].model.empty());
  CHECK(f.fits[1].lines.empty());
}

TEST_CASE("parse: fit block errors") {
  CHECK(parse_error("fit { data = 1 }").find("1:12: error: expected the data file name in double quotes after 'data'") != std::string::npos);
  CHECK(parse_error("fit { output fitted.rheo }").find("expected a file name in double quotes after 'output' for the fitted model") !=
        std::string::npos);
  CHECK(parse_error("fit m ]").find("expected '{' to open the fit block, found ']'") != std::string::npos);
  CHECK(parse_error("fit { method = exact, }").find("expected a setting `KEY = VALUE`, found '}'") != std::string::npos);
  CHECK(parse_error("fit { 2 }").find("or '}' to close the fit block, found '2'") != std::string::npos);
  CHECK(parse_error("model fit { }").find("expected a model name after 'model', found 'fit'") != std::string::npos);
}

TEST_CASE("parse: an argument records the byte range of its value expression") {
  const std::string text = "model m { param k0 = 300 N/mm in [1, 1000]  maxwell m1 (k = -(2 * k0) , tau = 4.335ms) }";
  ast::File f = parse("p.rheo", text);
  const auto& k0 = f.models.at(0).parameters.at(0);
  CHECK(text.substr(static_cast<std::size_t>(k0.value_begin), static_cast<std::size_t>(k0.value_end - k0.value_begin)) == "300 N/mm");
  const auto& args = f.models.at(0).elements.at(0).arguments;
  CHECK(text.substr(static_cast<std::size_t>(args[0].value_begin), static_cast<std::size_t>(args[0].value_end - args[0].value_begin)) == "-(2 * k0)");
  CHECK(text.substr(static_cast<std::size_t>(args[1].value_begin), static_cast<std::size_t>(args[1].value_end - args[1].value_begin)) == "4.335ms");
}

namespace {
std::string repeat(std::string_view text, int times) {
  std::string out;
  for (int i = 0; i < times; ++i) out += text;
  return out;
}
const ast::Expr& value_of_first_argument(const ast::File& f) { return *f.models.at(0).elements.at(0).arguments.at(0).value; }
}  // namespace

TEST_CASE("parse: blocks and expressions nest up to the limits of limits.hpp") {
  const int blocks = max_block_depth, levels = max_expression_depth;
  const ast::File deep = parse("p.rheo", "model m {\n" + repeat("series {\n", blocks) + "spring s (k = 1)\n" + repeat("}\n", blocks + 1));
  const ast::Element* e = &deep.models.at(0).elements.at(0);
  for (int i = 1; i < blocks; ++i) e = &e->children.at(0);
  CHECK(e->children.at(0).kind == "spring");
  // Levels as written: parentheses, unary minus and operators each add one.
  CHECK(value_of_first_argument(parse("p.rheo", "model m { spring s (k = 2 * (a + 1)) }")).depth == 4);
  CHECK(value_of_first_argument(parse("p.rheo", "model m { spring s (k = 1 + 2 + 3) }")).depth == 3);
  const std::string at_limit[] = {repeat("(", levels - 1) + "1" + repeat(")", levels - 1), repeat("-", levels - 1) + "1",
                                  repeat("1 + ", levels - 1) + "1", repeat("(", levels / 2) + "1" + repeat(" * 2)", levels / 2 - 1) + ")"};
  for (const auto& expression : at_limit) {
    CAPTURE(expression);
    CHECK(value_of_first_argument(parse("p.rheo", "model m { spring s (k = " + expression + ") }")).depth <= levels);
  }
}

TEST_CASE("parse: hostile nesting 10,000 deep is a parse error at the first level too deep, not a crash") {
  const int d = 10000;
  std::string alternating = "model m {\n  ";
  for (int i = 0; i < d; ++i) alternating += fmt::format("parallel {{ spring a{} (k = 1 N/mm) series {{ ", i);
  alternating += "spring s (k = 1 N/mm)" + repeat(" } }", d) + "\n}\n";
  const std::string error = parse_error(alternating);
  CHECK(error.find(fmt::format("error: blocks nested deeper than {} levels", max_block_depth)) != std::string::npos);
  // The 201st block keyword: 100 `parallel { spring aN (...) series { ` groups stand before it.
  CHECK(error.find(fmt::format("p.rheo:2:{}:", alternating.find("parallel { spring a100 ") - alternating.find('\n'))) == 0);
  for (const std::string& expression :
       {repeat("(", d) + "1" + repeat(")", d), repeat("-", d) + "1", repeat("1 + ", d) + "1", repeat("(1 + ", d) + "1" + repeat(")", d)}) {
    const std::string message = parse_error("model m { spring s (k = " + expression + ") }");
    CHECK(message.find(fmt::format("expression nested deeper than {} levels", max_expression_depth)) != std::string::npos);
  }
  CHECK(parse_error("model m { spring s (k = 1) }\nsimulate { harmonic frequency = " + repeat("(", d) + "1 Hz" + repeat(")", d) +
                    ", amplitude = 1 mm }")
            .find("expression nested deeper than") != std::string::npos);
  // The same limits hold for a setting given on the command line.
  CHECK_THROWS_WITH_AS(parse_setting_text("<command line>", "frequency = " + repeat("-", d) + "1 Hz"),
                       doctest::Contains("<command line>:1:212: error: expression nested deeper than"), CompileError);
}

TEST_CASE("parse: a file that is not UTF-8 text is an error at its first such byte, UTF-8 text parses") {
  CHECK(parse_error("model m {\n  spring s (k = 1 N/mm) \xff\n}\n").find("p.rheo:2:25: error: found byte 0xFF, which is not UTF-8") == 0);
  CHECK(parse_error(std::string("model m {\0}", 11)).find("p.rheo:1:10: error: found a NUL byte") == 0);
  // Non-ASCII UTF-8 in comments and strings is text; columns count bytes.
  const ast::File f = parse("p.rheo",
                            "# Prüfstand µ — 試験\nmodel m { spring s (k = 1 N/mm) }\nsimulate {\n  history file = \"straße.csv\" # ü\n}\n");
  CHECK(f.simulations.at(0).lines.at(0).settings.at(0).value.text == "straße.csv");
  // Outside them a non-ASCII character is reported whole.
  CHECK(parse_error("model m {\n  spring s (k = 1 µm)\n}\n").find("found 'µ'") != std::string::npos);
  // A unit with the micro sign is named in the ASCII spelling rheo reads.
  CHECK(parse_error("model m {\n  spring s (k = 1 N/µm)\n}\n").find("write 'N/um' for 'N/µm'") != std::string::npos);
  const std::string control = parse_error("model m { spring s (k = 1) \x1b[2J }");
  CHECK(control.find("found control character 0x1B") != std::string::npos);
  CHECK(control.find('\x1b') == std::string::npos);
}

TEST_CASE("parse: a word after a number that is no unit is named as such, a missing comma before a key is not") {
  const std::string nmm = parse_error("model m {\n  spring s (k = 1.5e3 Nmm)\n}\n");
  CHECK(nmm.find("p.rheo:2:23: error: expected ')' to close the argument list of 'spring s', found 'Nmm'; 'Nmm' is not a unit rheo "
                 "knows: use N, kN, mN, mm, m, cm, um, in, s, ms, us, min, Hz, kHz, kg, g, rad, Pa, kPa, MPa, GPa, deg, %, combined with") == 0);
  const std::string comma = parse_error("model m { spring s (k = 1) }\nsimulate { harmonic frequency = 1 Hz, amplitude = 1 cycles_max = 2 }\n");
  CHECK(comma.find("p.rheo:2:64: error: a setting needs its protocol: ") == 0);
  CHECK(comma.find("or a ',' is missing before the setting, found '='") != std::string::npos);
  CHECK(comma.find("is not a unit") == std::string::npos);
  // After a known unit the word is no unit's fault either.
  CHECK(parse_error("model m {\n  spring s (k = 1 N/mm extra)\n}\n").find("is not a unit") == std::string::npos);
}

}  // namespace parser_test
