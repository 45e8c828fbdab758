// `rheo export --abaqus/--ansys` end to end (#27 item 3): the written cards, read back as Abaqus
// and ANSYS read them (fe_card_reading.hpp), give `rheo simulate`'s harmonic storage and loss;
// geometry from the data line or the options; refusals at line:col; destinations checked before
// any work; no file written unless every one can be.
#include "cli_support.hpp"
#include "fe_card_reading.hpp"
#include "support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

namespace cli_fe_export_test {

namespace fs = std::filesystem;
using rheo::test::run_rheo;

namespace {

fs::path scratch() { return rheo::test::scratch_directory("cli-export"); }

// Writes TEXT to NAME in the scratch folder; returns its path.
std::string write(const std::string& name, const std::string& text) {
  const fs::path path = scratch() / name;
  std::ofstream(path) << text;
  return path.string();
}

const char* kModel = R"(model bushing {
  spring eq (k = 180 N/mm in [1, 1000])
  maxwell m1 (k = 420 N/mm, tau = 1.5 ms)
  series slow { spring s (k = 55 N/mm)  dashpot d (c = 22 N*s/mm) }
  springpot sp (k = 35 N/mm, alpha = 0.35, tau = 0.02 s, f_low = 0.05 Hz, f_high = 500 Hz)
}
simulate {
  harmonic frequency = [0.001, 0.04, 0.7, 3, 25, 180, 900, 20000] Hz, amplitude = 0.3 mm
}
)";

// Every point of `rheo simulate FILE --json`: frequency, storage, loss.
std::vector<std::array<double, 3>> simulated(const std::string& file) {
  const auto r = run_rheo(fmt::format("simulate {} --json", file));
  REQUIRE(r.code == 0);
  std::vector<std::array<double, 3>> out;
  const auto json = nlohmann::json::parse(r.out);
  for (const auto& p : json.at("points")) out.push_back({p["frequency"].get<double>(), p["storage"].get<double>(), p["loss"].get<double>()});
  REQUIRE(out.size() == 8);
  return out;
}

// The cards' storage and loss, K = E* / (modulus per stiffness), against the simulated ones.
void check_cards(const rheo::test::ReadMaterial& m, const std::vector<std::array<double, 3>>& points, double modulus_per_stiffness) {
  REQUIRE(!m.terms.empty());
  for (const auto& point : points) {
    const double f = point[0], storage = point[1], loss = point[2];  // not a structured binding: Clang 14 cannot capture one
    const auto k = rheo::test::complex_young(m, f) / modulus_per_stiffness;
    CHECK_MESSAGE(std::abs(k.real() / storage - 1.0) <= 1e-9, "storage at " << f << " Hz: " << k.real() << " vs " << storage);
    CHECK_MESSAGE(std::abs(k.imag() / loss - 1.0) <= 1e-9, "loss at " << f << " Hz: " << k.imag() << " vs " << loss);
  }
}

}  // namespace

TEST_CASE("rheo export: the Abaqus and ANSYS cards give rheo simulate's storage and loss, a springpot's chain included") {
  const std::string file = write("bushing.rheo", kModel);
  const auto points = simulated(file);
  const fs::path inp = scratch() / "bushing.inp", mac = scratch() / "bushing.mac";
  const auto r = run_rheo(fmt::format("export {} --abaqus {} --ansys {}", file, inp.string(), mac.string()));
  REQUIRE(r.code == 0);
  CHECK(r.err.find(fmt::format("written to {}", inp.string())) != std::string::npos);
  const std::string abaqus = rheo::test::read_file(inp.string()), ansys = rheo::test::read_file(mac.string());
  check_cards(rheo::test::read_abaqus(abaqus), points, 1.0);
  check_cards(rheo::test::read_ansys(ansys), points, 1.0);
  CHECK(rheo::test::read_abaqus(abaqus).instantaneous_moduli);
  CHECK(abaqus.starts_with(
      fmt::format("** Abaqus material of model 'bushing' from {}, written by rheo {} (rheo export).", file, RHEO_PROJECT_VERSION)));
  CHECK(ansys.starts_with(fmt::format("! ANSYS Mechanical APDL material of model 'bushing' from {}, written by rheo {}", file, RHEO_PROJECT_VERSION)));
  CHECK(abaqus.find("No specimen geometry") != std::string::npos);
  CHECK(abaqus.find("springpot sp (") != std::string::npos);
}

TEST_CASE("rheo export: the data line's area and height make the cards moduli, M = K h / A, and --modulus shear writes E = 2 (1 + nu) G") {
  const std::string file = write("specimen.rheo", std::string(kModel) + "fit {\n  data \"sweep.csv\", area = 40 mm^2, height = 20 mm\n}\n");
  const auto points = simulated(file);
  const fs::path inp = scratch() / "specimen.inp", mac = scratch() / "specimen.mac";
  REQUIRE(run_rheo(fmt::format("export {} --abaqus {} --ansys {} --modulus shear --poisson 0.45", file, inp.string(), mac.string())).code == 0);
  const std::string abaqus = rheo::test::read_file(inp.string());
  check_cards(rheo::test::read_abaqus(abaqus), points, 20.0 / 40.0 * 2.0 * 1.45);
  check_cards(rheo::test::read_ansys(rheo::test::read_file(mac.string())), points, 20.0 / 40.0 * 2.0 * 1.45);
  CHECK(abaqus.find(fmt::format("Specimen geometry from the data line at {}:11:8: area A = 40 mm^2, height h = 20 mm", file)) != std::string::npos);
  CHECK(abaqus.find("(--modulus shear)") != std::string::npos);
  // --area and --height take over; --no-geometry writes stiffness terms.
  REQUIRE(run_rheo(fmt::format("export {} --abaqus {} --area '1 cm^2' --height '5 mm'", file, inp.string())).code == 0);
  check_cards(rheo::test::read_abaqus(rheo::test::read_file(inp.string())), points, 5.0 / 100.0);
  REQUIRE(run_rheo(fmt::format("export {} --abaqus {} --no-geometry", file, inp.string())).code == 0);
  check_cards(rheo::test::read_abaqus(rheo::test::read_file(inp.string())), points, 1.0);
}

TEST_CASE("rheo export: elements without a Prony counterpart are refused at line:col, or left out by name and reported") {
  const std::string body = "model m {\n  spring k (k = 300 N/mm)\n  maxwell m1 (k = 100 N/mm, tau = 4 ms)\n";
  const std::string file = write("friction.rheo", body + "  friction f (k = 80 N/mm, fy = 5 N)\n}\n");
  const fs::path inp = scratch() / "friction.inp";
  fs::remove(inp);
  auto r = run_rheo(fmt::format("export {} --abaqus {}", file, inp.string()));
  CHECK(r.code == 3);
  CHECK(r.err.find(fmt::format("{}:4:3: error: model 'm': friction 'f' is rate-independent friction", file)) != std::string::npos);
  CHECK(r.err.find("--leave-out f") != std::string::npos);
  CHECK_FALSE(fs::exists(inp));
  r = run_rheo(fmt::format("export {} --abaqus {} --leave-out f", file, inp.string()));
  REQUIRE(r.code == 0);
  CHECK(r.err.find(fmt::format("rheo: left out friction 'f' ({}:4:3)", file)) != std::string::npos);
  const std::string abaqus = rheo::test::read_file(inp.string());
  CHECK(abaqus.find(fmt::format("** LEFT OUT (--leave-out): friction f ({}:4:3); these cards lack its force.", file)) != std::string::npos);
  // What is written is the model without f.
  const std::string without = write("without.rheo",
                                    body + "}\nsimulate {\n  harmonic frequency = [0.01, 0.2, 1, 5, 40, 100, 2000, 1e5] Hz, amplitude = 1 mm\n}\n");
  check_cards(rheo::test::read_abaqus(abaqus), simulated(without), 1.0);
  // A misspelt branch is a usage error.
  r = run_rheo(fmt::format("export {} --abaqus {} --leave-out g", file, inp.string()));
  CHECK(r.code == 2);
  CHECK(r.err.find("--leave-out 'g': model 'm' has no element of that name") != std::string::npos);
}

TEST_CASE("rheo export: destinations are checked before any work, and a failure writes nothing") {
  const std::string refused = write("refused.rheo", "model m {\n  yeoh y (D10 = 1, D20 = 0, D30 = 0)\n}\n");
  auto r = run_rheo(fmt::format("export {} --abaqus {}", refused, (scratch() / "absent" / "x.inp").string()));
  CHECK(r.code == 4);  // the destination, before the model is even read
  CHECK(r.err.find("does not exist") != std::string::npos);
  r = run_rheo(fmt::format("export {} --ansys {}", refused, scratch().string()));
  CHECK(r.code == 4);
  CHECK(r.err.find("the output is a directory") != std::string::npos);
  CHECK(run_rheo(fmt::format("export {}", refused)).code == 2);  // nothing to export
  // ANSYS cannot take 130 terms: neither file is written, and an earlier one stays as it was.
  const std::string wide = write(
      "wide.rheo",
      "model w {\n  spring k (k = 1 N/mm)\n  springpot sp (k = 2 N/mm, alpha = 0.5, tau = 1 s, f_low = 1e-15 Hz, f_high = 1e15 Hz)\n}\n");
  const fs::path inp = scratch() / "wide.inp", mac = scratch() / "wide.mac";
  fs::remove(inp);
  std::ofstream(mac) << "earlier\n";
  r = run_rheo(fmt::format("export {} --abaqus {} --ansys {}", wide, inp.string(), mac.string()));
  CHECK(r.code == 3);
  CHECK(r.err.find(fmt::format("{}:3:3: error: model 'w' makes", wide)) != std::string::npos);
  CHECK_FALSE(fs::exists(inp));
  CHECK(rheo::test::read_file(mac.string()) == "earlier\n");
  CHECK(run_rheo(fmt::format("export {} --abaqus {}", wide, inp.string())).code == 0);  // Abaqus takes them all
  // A geometry the options cannot give is a usage error before anything runs.
  r = run_rheo(fmt::format("export {} --abaqus {} --area '40 mm'  --height '2 mm'", wide, inp.string()));
  CHECK(r.code == 2);
  CHECK(r.err.find("--area '40 mm' is a length (mm), not an area (mm^2)") != std::string::npos);
  CHECK(run_rheo(fmt::format("export {} --abaqus {} --area '40 mm^2'", wide, inp.string())).code == 2);
  // Two data lines with different specimens: say which, and how to choose.
  const std::string two = write("two.rheo", std::string(kModel) +
                                                "fit {\n  data \"a.csv\", area = 40 mm^2, height = 20 mm\n"
                                                "  data \"b.csv\", area = 50 mm^2, height = 20 mm\n}\n");
  r = run_rheo(fmt::format("export {} --abaqus {}", two, inp.string()));
  CHECK(r.code == 2);
  CHECK(r.err.find("give two specimen geometries") != std::string::npos);
}

}  // namespace cli_fe_export_test
