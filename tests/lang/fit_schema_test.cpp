#include "lang/fit_schema.hpp"

#include "lang/frontend.hpp"
#include "lang/parser.hpp"

#include <doctest/doctest.h>

namespace fit_schema_test {

using namespace rheo::lang;

namespace {
const char* kModel = R"(model m {
  param k0 = 300 N/mm in [10, 5000]
  spring   main (k = k0)
  maxwell  m1   (k = 61.476 N/mm in [1, 1000], tau = 4.335 ms in [0.1, 100])
  friction f1   (k = 1016.6 N/mm, uy = 101.58 um in [1, 1000])
}
)";

std::vector<std::string> free_paths(const Program& p, const FitDirective& f) {
  std::vector<std::string> out;
  for (int i : f.free) out.push_back(p.find_model(f.model)->parameters[static_cast<std::size_t>(i)].path);
  return out;
}
}  // namespace

TEST_CASE("check_fit: settings in internal units, data lines with weights, output, free/fixed are not settings") {
  Program p = compile_source("f.rheo", std::string(kModel) + R"(fit m {
  data "data/a.csv"
  data "b.csv", weight = 0.5
  objective = least_squares, stiffness_weight = 0.25
  method = approximate, optimizer = sbplx, max_evaluations = 100, starts = 3, seed = 0, tolerance = 1e-6
  definition = thesis, steps_per_cycle = 512, time_limit = 2 min
  free = [m1.tau, k0]
  output "fitted.rheo"
})");
  REQUIRE(p.fits.size() == 1);
  const FitDirective& f = p.fits[0];
  CHECK(f.model == "m");
  REQUIRE(f.data.size() == 2);
  CHECK(f.data[0].file == "data/a.csv");
  CHECK(f.data[0].weight == 1.0);
  CHECK(f.data[1].weight == 0.5);
  CHECK(f.data[1].where.line == 9);
  CHECK(f.data[1].where.column == 8);
  CHECK(f.output == "fitted.rheo");
  CHECK(f.where.line == 7);
  CHECK(f.settings.objective == FitObjective::least_squares);
  CHECK(f.settings.stiffness_weight == 0.25);
  CHECK(f.settings.method == FitMethod::approximate);
  CHECK(f.settings.optimizer == Optimizer::sbplx);
  CHECK(f.settings.max_evaluations == 100);
  CHECK(f.settings.starts == 3);
  CHECK(f.settings.seed == 0);
  CHECK(f.settings.tolerance == 1e-6);
  CHECK(f.settings.definition == HarmonicDefinition::thesis);
  CHECK(f.settings.steps_per_cycle == 512);
  CHECK(f.settings.time_limit == 120.0);                                // seconds
  CHECK(f.settings.solver == SolverChoice::automatic);                  // not given: the default
  CHECK(free_paths(p, f) == std::vector<std::string>{"k0", "m1.tau"});  // sorted by parameter index
}

TEST_CASE("check_fit: a block without settings takes the defaults of fit_settings.hpp") {
  const Program p = compile_source("f.rheo", std::string(kModel) + "fit {}\n");
  const FitSettings& s = p.fits.at(0).settings;
  CHECK(s.objective == FitObjective::phi);
  CHECK_FALSE(s.stiffness_weight.has_value());
  CHECK(s.method == FitMethod::exact);
  CHECK(s.optimizer == Optimizer::automatic);
  CHECK(word_of(s.optimizer) == "default");
  CHECK_FALSE(s.max_evaluations.has_value());
  CHECK_FALSE(s.starts.has_value());
  CHECK_FALSE(s.tolerance.has_value());
  CHECK(s.seed == 1);
  CHECK(s.definition == HarmonicDefinition::thesis);
  CHECK_FALSE(s.steps_per_cycle.has_value());
  CHECK(s.solver == SolverChoice::automatic);
}

TEST_CASE("check_fit: the free set is every bounded parameter, restricted by free, less fixed") {
  Program p = compile_source("f.rheo", std::string(kModel) + "fit {}\nfit m { fixed = [m1.k, f1.k] }\nfit { free = [m1.k, f1.uy], fixed = [f1.uy] }");
  REQUIRE(p.fits.size() == 3);
  CHECK(free_paths(p, p.fits[0]) == std::vector<std::string>{"k0", "m1.k", "m1.tau", "f1.uy"});
  CHECK(free_paths(p, p.fits[1]) == std::vector<std::string>{"k0", "m1.tau", "f1.uy"});
  CHECK(free_paths(p, p.fits[2]) == std::vector<std::string>{"m1.k"});
  CHECK(p.fits[0].free == default_free_parameters(*p.find_model("m")));
  CHECK(p.fits[0].output.empty());
  CHECK(p.fits[0].data.empty());
}

TEST_CASE("check_fit: without a usable model only the shape of free/fixed is checked") {
  ast::File file = parse("f.rheo", "fit { free = [a.b], fixed = [1], method = exact }");
  std::vector<Diagnostic> errors;
  FitDirective f = check_fit(file.fits.at(0), "", nullptr, errors);
  REQUIRE(errors.size() == 1);
  CHECK(errors[0].message == "fixed lists parameters by path, not values; e.g. `fixed = [m1.k, m1.tau]`");
  CHECK(f.free.empty());
  CHECK(f.settings.method == FitMethod::exact);
}

TEST_CASE("check_fit_setting and parse_fit_setting: the fit schema for one setting") {
  std::vector<Diagnostic> errors;
  auto s = check_fit_setting(parse_setting_text("c", "method = corrected"), errors);
  REQUIRE(s);
  CHECK(s->text == "corrected");
  CHECK_FALSE(check_fit_setting(parse_setting_text("c", "free = [m1.k]"), errors));
  REQUIRE(errors.size() == 1);
  CHECK(errors[0].message.find("give it in the fit block") != std::string::npos);
  CHECK(parse_fit_setting("max_evaluations = 500").values == std::vector<double>{500.0});
  CHECK_THROWS_WITH_AS(parse_fit_setting("stiffness_weight = 2"), doctest::Contains("stiffness_weight must be between 0 and 1, got 2"), CompileError);
  CHECK(fit_setting_keys().front() == "objective");
  CHECK(fit_setting_keys().size() == 14);
  CHECK_THROWS_WITH_AS(parse_fit_setting("time_limit = 60 N"), doctest::Contains("time_limit"), CompileError);
  CHECK_THROWS_WITH_AS(parse_fit_setting("time_limit = -1 s"), doctest::Contains("time_limit"), CompileError);
}

TEST_CASE("a data line says how its file is read: columns by role, a TRIOS step, geometry, an amplitude as a length or a strain") {
  Program p = compile_source("f.rheo", std::string(kModel) + R"(fit m {
  data "dma.csv", columns = "frequency = f, storage = E_stor, loss = E_loss", area = 314 mm^2, height = 10 mm, amplitude = 0.1 %
  data "rig.txt", step = "Amplitude sweep", amplitude = 20 um
})");
  REQUIRE(p.fits.size() == 1);
  const auto& d = p.fits[0].data;
  REQUIRE(d.size() == 2);
  REQUIRE(d[0].columns.size() == 3);
  CHECK(d[0].columns[1].role == "storage");
  CHECK(d[0].columns[1].name == "E_stor");
  CHECK(d[0].area == 314.0);
  CHECK(d[0].height == 10.0);
  CHECK(d[0].amplitude == doctest::Approx(0.001).scale(0.0));
  CHECK(d[0].amplitude_is_strain);
  CHECK(d[1].step == "Amplitude sweep");
  CHECK(d[1].amplitude == doctest::Approx(0.02).scale(0.0));
  CHECK_FALSE(d[1].amplitude_is_strain);
}

TEST_CASE("data line settings that cannot be read are errors at the setting") {
  auto error_of = [](const std::string& line) {
    try {
      compile_source("f.rheo", std::string(kModel) + "fit m {\n  data \"a.csv\", " + line + "\n}\n");
    } catch (const CompileError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(error_of("columns = \"frequency f\"").find("columns takes 'role = column name' pairs separated by commas") != std::string::npos);
  CHECK(error_of("columns = \"temperature = T\"").find("columns: 'temperature' is not a role rheo reads; use time, displacement") !=
        std::string::npos);
  CHECK(error_of("columns = \"loss = a, loss = b\"").find("columns names the 'loss' column twice") != std::string::npos);
  CHECK(error_of("area = 10 mm").find("area") != std::string::npos);
  CHECK(error_of("height = -1 mm").find("height") != std::string::npos);
  CHECK(error_of("amplitude = 1 N").find("or a strain, e.g. amplitude = 0.1 %") != std::string::npos);
  CHECK(error_of("step = 3").find("step takes a text in double quotes") != std::string::npos);
  CHECK(error_of("colour = \"red\"").find("colour") != std::string::npos);
  CHECK(error_of("duplicates = sum").find("duplicates must be one of: average, error (got 'sum')") != std::string::npos);
}

TEST_CASE("a data line's duplicates: average by default, or error") {
  Program p = compile_source("f.rheo", std::string(kModel) + "fit m {\n  data \"a.csv\"\n  data \"b.csv\", duplicates = error\n}\n");
  REQUIRE(p.fits.at(0).data.size() == 2);
  CHECK(p.fits[0].data[0].duplicates == DuplicatePoints::average);
  CHECK(p.fits[0].data[1].duplicates == DuplicatePoints::error);
  CHECK(word_of(DuplicatePoints::average) == "average");
  CHECK(duplicate_points_named("error") == DuplicatePoints::error);
}

TEST_CASE("a data line's force_offset: a force with its unit (any sign), or free, its value's byte range is kept") {
  const std::string text = std::string(kModel) +
                           "fit m {\n  data \"a.csv\"\n  data \"b.csv\", force_offset = -0.12 kN\n  data \"c.csv\", force_offset = free\n}\n";
  Program p = compile_source("f.rheo", text);
  REQUIRE(p.fits.at(0).data.size() == 3);
  const auto& data = p.fits[0].data;
  CHECK_FALSE(data[0].force_offset.given);
  CHECK(data[1].force_offset.given);
  CHECK_FALSE(data[1].force_offset.free);
  CHECK(data[1].force_offset.value == doctest::Approx(-120.0));
  CHECK(text.substr(static_cast<std::size_t>(data[1].force_offset.value_begin),
                    static_cast<std::size_t>(data[1].force_offset.value_end - data[1].force_offset.value_begin)) == "-0.12 kN");
  CHECK(data[2].force_offset.free);
  CHECK(text.substr(static_cast<std::size_t>(data[2].force_offset.value_begin),
                    static_cast<std::size_t>(data[2].force_offset.value_end - data[2].force_offset.value_begin)) == "free");
  CHECK(data[2].force_offset.where.line == data[2].where.line);
}

TEST_CASE("a force_offset without a force unit is an error at its value, saying what to write") {
  auto error_of = [](const std::string& setting) {
    try {
      compile_source("f.rheo", std::string(kModel) + "fit m {\n  data \"a.csv\", " + setting + "\n}\n");
    } catch (const CompileError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string plain = error_of("force_offset = 120");
  CHECK(plain.find("f.rheo:8:32") != std::string::npos);
  CHECK(plain.find("force_offset needs a force unit; e.g. force_offset = 120 N, or force_offset = free to fit it") != std::string::npos);
  const std::string length = error_of("force_offset = 120 mm");
  CHECK(length.find("f.rheo:8:32") != std::string::npos);
  CHECK(length.find("force_offset expects a force (N), got a length (mm)") != std::string::npos);
  CHECK(length.find("or force_offset = free to fit it") != std::string::npos);
  CHECK(error_of("force_offset = fixed").find("or force_offset = free to fit it") != std::string::npos);
  CHECK(error_of("force_offset = 1 N, force_offset = free").find("duplicate setting 'force_offset'") != std::string::npos);
}

TEST_CASE("--data takes force_offset like a data line") {
  const FitData d = parse_data_option("rig.csv, force_offset = free");
  CHECK(d.force_offset.free);
  CHECK_THROWS_AS(parse_data_option("rig.csv, force_offset = 3 s"), CompileError);
}

}  // namespace fit_schema_test
