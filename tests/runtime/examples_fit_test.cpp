// The examples that fit, diagnose and refine (examples_test.cpp runs the others), through the
// real binary, against what their data were made from (examples/data/README.md): the generating
// parameters, the noise put in, and the noise floor of each measured file, the err (6.1) of its
// noise-free grid against it (examples_support.hpp), which a fit of the true structure reaches.
// errs documented in docs/tutorial.md are rheo's own output: those checks are regression checks,
// in test cases named so, each beside an independent check of the same quantity.
#include "examples_support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <tuple>
#include <vector>

namespace examples_fit_test {

using namespace rheo;
using namespace rheo::test::examples;

TEST_CASE("fitting specimen D to its harmonic and static tests at once brings both down to the data's noise") {
  const fs::path dir = scratch();
  const fs::path report = dir / "all.json", fitted = dir / "all_fitted.rheo";
  REQUIRE(rheo_run(fmt::format("fit {} --json -o {} > {}", example("specimen_d_fit_all.rheo"), fitted.string(), report.string())) == 0);
  std::ifstream in(report);
  const auto j = nlohmann::json::parse(in);
  REQUIRE(j["data"].size() == 2);
  for (const auto& set : j["data"]) {
    CAPTURE(set["file"].get<std::string>());
    if (set["kind"] == "history") {
      // RMS force residual relative to max |F|: the noise is 0.3 % of the maximum.
      CHECK(set["err"].get<double>() < 0.0035);
    } else {
      // At most the noise floor: err (6.1) of the noise-free grid against this file, 1.5043e-3.
      CHECK(set["err"].get<double>() <= grid_err(data("specimen_D_reference.csv"), data("specimen_D_harmonic.csv")));
    }
  }
  CHECK(fs::exists(fitted));
}

// The tutorial's errs (docs/tutorial.md section 8) are rheo's own output: regression checks. The
// independent check is the file's noise floor, the err (6.1) of its noise-free grid against it
// (1.8327e-3; the grid is accurate to 0.06 % and 0.03 deg, examples/data/README.md, which moves
// the floor by about 1 %: the exact periodic state of the generating model scores 1.8502e-3):
// the coupled structure holds the generating model and must reach it within 5 %, the uncoupled
// one cannot follow the coupling and stays far above it.
TEST_CASE(
    "regression: hydrobushing's coupled topology reaches the tutorial's err and the file's noise floor, over 3 times below the uncoupled 2 Maxwell + 4 friction model") {
  const fs::path dir = scratch();
  const fs::path uncoupled = dir / "uncoupled.json", coupled = dir / "coupled.json";
  REQUIRE(rheo_run(fmt::format("fit {} --block 1 --json > {}", example("hydrobushing_fit.rheo"), uncoupled.string())) == 0);
  REQUIRE(rheo_run(fmt::format("fit {} --block 2 --json > {}", example("hydrobushing_fit.rheo"), coupled.string())) == 0);
  std::ifstream u(uncoupled), c(coupled);
  const auto ju = nlohmann::json::parse(u), jc = nlohmann::json::parse(c);
  const double err_uncoupled = ju["err"].get<double>(), err_coupled = jc["err"].get<double>();
  MESSAGE(fmt::format("hydrobushing err (6.1): uncoupled {:.4e}, coupled {:.4e} (ratio {:.1f})", err_uncoupled, err_coupled,
                      err_uncoupled / err_coupled));
  CHECK(err_uncoupled > 3.0 * err_coupled);
  const double floor = grid_err(data("hydrobushing_reference.csv"), data("hydrobushing_harmonic.csv"));
  CHECK(err_coupled <= 1.05 * floor);
  CHECK(err_uncoupled > 5.0 * floor);
  CHECK(err_uncoupled == doctest::Approx(2.3750e-2).epsilon(0.01).scale(0.0));  // regression: docs/tutorial.md section 8
  CHECK(err_coupled <= 1.05 * 1.8195e-3);                                       // regression: docs/tutorial.md section 8, 13 times lower
}

// The end of docs/tutorial.md section 8: without being told the topology, rheo diagnose finds
// the coupling the uncoupled model misses, adds a slider-capped fluid column with its walls'
// spring (the column alone stopped at 6.87e-3, 3.7 times the floor) and refits to the file's
// noise floor (the generating model's exact periodic state scores 1.8502e-3).
TEST_CASE("hydrobushing: rheo diagnose names the uncoupled model's missing coupling and reaches the noise floor with the column's walls") {
  const fs::path dir = scratch();
  const fs::path summary = dir / "diagnose.json", refined = dir / "hydro_refined.rheo";
  REQUIRE(rheo_run(fmt::format("diagnose {} --block 1 --threads 2 --json -o {} > {}", example("hydrobushing_fit.rheo"), refined.string(),
                               summary.string())) == 0);
  std::ifstream in(summary);
  const auto j = nlohmann::json::parse(in);
  const double before = j["err_before"].get<double>(), after = j["err_after"].get<double>();
  MESSAGE(fmt::format("hydrobushing diagnose: {}, err (6.1) {:.4e} -> {:.4e} ({:.2f} times lower)", j["effect"].get<std::string>(), before, after,
                      before / after));
  CHECK(j["effect"] == "coupled-amplitude-frequency");
  // `before` is the uncoupled fit of block 1: `rheo fit --block 1`, a second path, gives it too.
  const fs::path fit_json = dir / "block1.json";
  REQUIRE(rheo_run(fmt::format("fit {} --block 1 --json > {}", example("hydrobushing_fit.rheo"), fit_json.string())) == 0);
  CHECK(before == doctest::Approx(read_json(fit_json)["err"].get<double>()).epsilon(1e-3).scale(0.0));
  CHECK(after <= before / 3.0);
  CHECK(after <= 1.05 * grid_err(data("hydrobushing_reference.csv"), data("hydrobushing_harmonic.csv")));
  REQUIRE(j["added"].size() == 1);
  const std::string statement = j["added"][0]["statement"].dump();
  CHECK(statement.find("slider") != std::string::npos);
  CHECK(statement.find("inerter") != std::string::npos);
  CHECK(statement.find("spring  bulge") != std::string::npos);
  CHECK(rheo_run(fmt::format("check {} > /dev/null", refined.string())) == 0);
}

// The diagnosis does not hang on the last bits: with every measured stiffness scaled by 1 - 1e-9
// the column's first refit stops above its own limit without inertia (err 0.0131 against
// 0.0120), and before the restart from the limit's optimum the limit was chosen and the gap fell
// to 0.012 only. The column is searched again from there and the refined model is as good.
TEST_CASE("hydrobushing: rheo diagnose finds the fluid column also when the data move by 1e-9") {
  const fs::path dir = scratch() / "perturbed";
  fs::create_directories(dir / "data");
  fs::copy_file(example("hydrobushing_fit.rheo"), dir / "hydrobushing_fit.rheo", fs::copy_options::overwrite_existing);
  std::ifstream in(fs::path(example("data")) / "hydrobushing_harmonic.csv");
  std::ofstream out(dir / "data" / "hydrobushing_harmonic.csv");
  int rows = 0;
  for (std::string line; std::getline(in, line);) {
    double a = 0.0, f = 0.0, k = 0.0, phase = 0.0;
    if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &a, &f, &k, &phase) == 4) {
      line = fmt::format("{:.3f},{:.2f},{:.10f},{:.4f}", a, f, k * (1.0 - 1e-9), phase), ++rows;
    }
    out << line << "\n";
  }
  out.close();
  REQUIRE(rows == 147);
  const fs::path summary = dir / "diagnose.json";
  REQUIRE(rheo_run(fmt::format("diagnose {} --block 1 --threads 2 --json > {}", (dir / "hydrobushing_fit.rheo").string(), summary.string())) == 0);
  const auto j = read_json(summary);
  CHECK(j["effect"] == "coupled-amplitude-frequency");
  CHECK(j["err_after"].get<double>() <= j["err_before"].get<double>() / 3.0);
  REQUIRE(j["added"].size() == 1);
  CHECK(j["added"][0]["statement"].dump().find("inerter") != std::string::npos);
}

// The documented errs are rheo's own output (regression checks). The independent check: the true
// structure is fitted, so a fit reaches the noise floor of its file, the err (6.1) of the
// noise-free reference grid against it (examples_support.hpp); a fit absorbs a little of the
// noise, so it ends at or below it.
TEST_CASE("regression: the example fits of specimens A-D reach their documented err and their files' noise floor, the fitted files score it again") {
  // docs/tutorial.md: A 1.1412e-2 (Table D.4: 1.1869e-2), B 7.0444e-3 (Table D.4: 7.8852e-3),
  // C 2.7877e-3 (Table D.4: 2.8506e-3), D 1.4949e-3 (noise floor 1.5043e-3).
  // A fixed seed repeats bit for bit on one machine; 1e-3 relative leaves room for another libm
  // (scale 0: doctest's default scale of 1 would make the tolerance 1e-3 absolute).
  for (const auto& specimen : {std::tuple{"specimen_a_fit.rheo", 'A', 1.1412e-2}, std::tuple{"specimen_b_fit.rheo", 'B', 7.0444e-3},
                               std::tuple{"specimen_c_fit.rheo", 'C', 2.7877e-3}, std::tuple{"specimen_d_fit.rheo", 'D', 1.4949e-3}}) {
    const char* const file = std::get<0>(specimen);  // not a structured binding: Clang 14 cannot capture one
    const char letter = std::get<1>(specimen);
    const double documented = std::get<2>(specimen);
    const std::string harmonic = fmt::format("specimen_{}_harmonic.csv", letter), reference = fmt::format("specimen_{}_reference.csv", letter);
    const fs::path json = scratch() / (std::string(file) + ".json"), fitted = scratch() / (std::string(file) + ".fitted.rheo");
    REQUIRE(rheo_run(fmt::format("fit {} --json -o {} > {}", example(file), fitted.string(), json.string())) == 0);
    std::ifstream in(json);
    const auto summary = nlohmann::json::parse(in);
    const double err = summary.at("err").get<double>();
    CAPTURE(file);
    CHECK(err == doctest::Approx(documented).epsilon(1e-3).scale(0.0));  // regression: docs/tutorial.md
    CHECK(err <= grid_err(data(reference), data(harmonic)));
    // A's noisy file has one phase below zero (3 mm, 0.5 Hz, row 137): kept, its damping term
    // left out of eq. 5.1, and a note says so. The other files have none.
    const auto& notes = summary.at("notes");
    if (std::string(file) == "specimen_a_fit.rheo") {
      REQUIRE(notes.size() == 1);
      CHECK(notes[0].get<std::string>().find(":137: phase -0.0216 deg <= 0") != std::string::npos);
      int left_out = 0;
      for (const auto& point : summary.at("data")[0].at("residuals"))
        if (point.at("amplitude_mm") == 3.0 && point.at("frequency_hz") == 0.5) {
          ++left_out;
          CHECK(point.at("damping_residual").get<double>() == 0.0);
        }
      CHECK(left_out == 1);
    } else {
      CHECK(notes.empty());
    }
    // The written model, read back and evaluated by `rheo report`, scores the same err.
    const fs::path page = scratch() / (std::string(file) + ".html");
    REQUIRE(rheo_run(fmt::format("report {} --data {} -o {} > /dev/null 2>&1", fitted.string(), data(harmonic), page.string())) == 0);
    std::ifstream html_in(page);
    const std::string html((std::istreambuf_iterator<char>(html_in)), std::istreambuf_iterator<char>());
    CHECK(html.find(fmt::format("err (6.1) = {:.4e}", err)) != std::string::npos);
  }
}

TEST_CASE("examples/prony_fit.rheo: the 21 stiffnesses of the generating Prony series, to 1e-6, in one solve") {
  // examples/data/README.md: k_inf = 50 N/mm; arm i (tau = 10^(i - 9) s) has
  // k_i = 20 + 180 exp(-((i - 10.5)/5)^2) N/mm rounded to 4 digits.
  const std::vector<double> arms{24.87, 30.0,  38.97, 53.21, 73.68, 100.1, 130.3, 160.2, 184.5, 198.2,
                                 198.2, 184.5, 160.2, 130.3, 100.1, 73.68, 53.21, 38.97, 30.0,  24.87};
  const fs::path json = scratch() / "prony.json", fitted = scratch() / "prony_fitted.rheo";
  REQUIRE(rheo_run(fmt::format("fit {} --json -o {} > {}", example("prony_fit.rheo"), fitted.string(), json.string())) == 0);
  std::ifstream in(json);
  const auto summary = nlohmann::json::parse(in);
  CHECK(summary.at("evaluations").get<int>() <= 22);  // the basis of 21 scales and the start: no search
  CHECK(summary.at("err").get<double>() < 1e-10);
  int checked = 0;
  for (const auto& p : summary.at("parameters")) {
    if (!p.at("free").get<bool>()) continue;  // the taus, held
    ++checked;
    const std::string name = p.at("path").get<std::string>();
    const double value = p.at("value").get<double>();
    CAPTURE(name);
    if (name == "equilibrium.k") CHECK(value == doctest::Approx(50.0).epsilon(1e-6));
    else CHECK(value == doctest::Approx(arms.at(std::stoul(name.substr(1, name.find('.') - 1)) - 1)).epsilon(1e-6));
  }
  CHECK(checked == 21);
}

TEST_CASE("examples/dma_master_curve_fit.rheo: a DMA export over 26 decades read through its geometry, every stiffness to 1e-6") {
  // examples/data/README.md: E_inf = 2 MPa, arm i (tau = 10^(i - 15) s) E_i = 0.5 + 300 exp(-((i - 9)/4)^2)
  // MPa rounded to 4 digits; a 40 mm^2 x 20 mm bar makes each 2 E N/mm.
  auto modulus = [](int i) { return std::stod(fmt::format("{:.4g}", 0.5 + 300.0 * std::exp(-std::pow((i - 9) / 4.0, 2)))); };
  const fs::path json = scratch() / "dma.json", fitted = scratch() / "dma_fitted.rheo";
  REQUIRE(rheo_run(fmt::format("fit {} --json -o {} > {}", example("dma_master_curve_fit.rheo"), fitted.string(), json.string())) == 0);
  std::ifstream in(json);
  const auto summary = nlohmann::json::parse(in);
  CHECK(summary.at("err").get<double>() < 1e-10);
  int checked = 0;
  for (const auto& p : summary.at("parameters")) {
    if (!p.at("free").get<bool>()) continue;  // the taus, held
    ++checked;
    const std::string name = p.at("path").get<std::string>();
    const double value = p.at("value").get<double>();
    CAPTURE(name);
    if (name == "equilibrium.k") CHECK(value == doctest::Approx(2.0 * 2.0).epsilon(1e-6));
    else CHECK(value == doctest::Approx(2.0 * modulus(std::stoi(name.substr(1, name.find('.') - 1)))).epsilon(1e-6));
  }
  CHECK(checked == 26);
}

// The coupled bushing (#23): the generating model of examples/data/README.md explains the data to
// their noise (1 % in stiffness, 0.15 deg in phase), and a short fit from the example's generic
// start falls more than tenfold in err. The default fit is bench/ work (BM_CoupledBushing_Fit).
TEST_CASE("examples/coupled_bushing_fit.rheo: the README's generating model scores at the noise, a short fit from the example's start") {
  const fs::path dir = scratch();
  const fs::path truth = dir / "coupled_truth.rheo", grid = dir / "coupled_truth.csv";
  {
    std::ofstream out(truth);
    out << "model truth {\n  spring k0 (k = 500 N/mm)  maxwell m1 (k = 200 N/mm, tau = 2 ms)  maxwell m2 (k = 100 N/mm, tau = 50 ms)\n"
           "  friction f1 (k = 150 N/mm, uy = 0.02 mm)  friction f2 (k = 80 N/mm, uy = 0.1 mm)  friction f3 (k = 40 N/mm, uy = 0.5 mm)\n"
           "  series arm { slider s (fy = 45 N)  maxwell ma (k = 400 N/mm, tau = 10 ms) }\n}\n"
           "simulate { harmonic frequency = 1 Hz .. 41 Hz step 2 Hz, amplitude = [0.1, 0.2, 0.5, 0.8, 1.0, 1.5, 2.0] mm }\n";
  }
  REQUIRE(rheo_run(fmt::format("simulate {} -o {}", truth.string(), grid.string())) == 0);
  const runtime::Table got = runtime::read_table(grid.string());
  const runtime::Table want = runtime::read_table(data("coupled_bushing_harmonic.csv"));
  REQUIRE(got.rows.size() == 147);
  REQUIRE(want.rows.size() == 147);
  double stiffness2 = 0.0, phase2 = 0.0;
  for (std::size_t i = 0; i < want.rows.size(); ++i) {
    REQUIRE(std::abs(got.columns[0][i] - want.columns[0][i]) < 1e-9);
    REQUIRE(std::abs(got.columns[1][i] - want.columns[1][i]) < 1e-9);
    stiffness2 += std::pow(want.columns[2][i] / got.columns[2][i] - 1.0, 2);
    phase2 += std::pow((want.columns[3][i] - got.columns[3][i]) * 180.0 / M_PI, 2);
  }
  const double stiffness_rms = std::sqrt(stiffness2 / 147.0), phase_rms = std::sqrt(phase2 / 147.0);
  MESSAGE(fmt::format("coupled bushing data vs generating model: RMS stiffness {:.4f}, phase {:.4f} deg", stiffness_rms, phase_rms));
  CHECK(stiffness_rms == doctest::Approx(0.01).epsilon(0.15).scale(0.0));  // 147 draws: the sample RMS within ~6 % (1 sigma)
  CHECK(phase_rms == doctest::Approx(0.15).epsilon(0.15).scale(0.0));

  const fs::path fitted = dir / "coupled_fitted.rheo", start_json = dir / "coupled_start.json", fit_json = dir / "coupled_fit.json";
  REQUIRE(rheo_run(fmt::format("fit {} --max-evaluations 1 --json > {}", example("coupled_bushing_fit.rheo"), start_json.string())) == 0);
  REQUIRE(rheo_run(fmt::format("fit {} --starts 1 --max-evaluations 120 --threads 2 --json -o {} > {}", example("coupled_bushing_fit.rheo"),
                               fitted.string(), fit_json.string())) == 0);
  std::ifstream s(start_json), f(fit_json);
  const auto js = nlohmann::json::parse(s), jf = nlohmann::json::parse(f);
  MESSAGE(fmt::format("coupled bushing: err at the start {:.4e}, after 120 evaluations {:.4e}", js["err"].get<double>(), jf["err"].get<double>()));
  CHECK(jf["err"].get<double>() < js["err"].get<double>() / 10.0);
  CHECK(rheo_run(fmt::format("check {}", fitted.string())) == 0);
  // The Jacobian columns start their shootings from the base point's periodic states
  // (closed_form/pwl_warm_start.hpp), the same whichever thread evaluates them: one thread
  // writes the same model, digit for digit.
  const fs::path fitted_one = dir / "coupled_fitted_1.rheo", fit_one_json = dir / "coupled_fit_1.json";
  REQUIRE(rheo_run(fmt::format("fit {} --starts 1 --max-evaluations 120 --threads 1 --json -o {} > {}", example("coupled_bushing_fit.rheo"),
                               fitted_one.string(), fit_one_json.string())) == 0);
  std::ifstream f1(fit_one_json);
  CHECK(nlohmann::json::parse(f1)["err"].get<double>() == jf["err"].get<double>());
  const auto text = [](const fs::path& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  CHECK(text(fitted_one) == text(fitted));
}

// A real TRIOS export (#25) read from a data line alone: the step, the geometry, the moduli.
TEST_CASE("examples/trios_amplitude_sweep_fit.rheo: the amplitude sweep read from the export as it is, fitted to a few per cent") {
  const fs::path fitted = scratch() / "trios_fitted.rheo", json_path = scratch() / "trios.json";
  REQUIRE(rheo_run(fmt::format("fit {} --json -o {} > {}", example("trios_amplitude_sweep_fit.rheo"), fitted.string(), json_path.string())) == 0);
  std::ifstream in(json_path);
  const auto summary = nlohmann::json::parse(in);
  const auto& set = summary.at("data").at(0);
  CHECK(set.at("step") == "Amplitude sweep - 1");
  CHECK(set.at("area_mm2").get<double>() == 490.874);
  CHECK(set.at("points").get<int>() == 29);
  // The export's first row: |G*| 0.01838055859375 MPa (its 'Complex modulus' and 'Phase angle' are
  // read before storage and loss), strain 0.00989877906867619 %; 490.874 mm^2 over a 1 mm gap.
  const auto& first = set.at("residuals").at(0);
  CHECK(first.at("stiffness_measured").get<double>() == doctest::Approx(0.01838055859375 * 490.874).epsilon(1e-9));
  CHECK(first.at("phase_measured_deg").get<double>() == doctest::Approx(2.16277233398213).epsilon(1e-9));
  CHECK(first.at("amplitude_mm").get<double>() == doctest::Approx(0.00989877906867619e-2).epsilon(1e-9).scale(0.0));
  MESSAGE(fmt::format("TRIOS amplitude sweep: err {:.4e}", summary.at("err").get<double>()));
  CHECK(summary.at("err").get<double>() < 0.06);  // 4.9e-2 with three friction elements (README of examples/data/real)
  CHECK(rheo_run(fmt::format("check {}", fitted.string())) == 0);
}

// A rig export from a preloaded start with a load-cell offset (#25 items 1, 2, 4): the rig's own
// file, read with only a data line; every parameter of the generating model (specimen D, Appendix
// D; examples/data/README.md) and the 150 N offset come back from a generic start.
TEST_CASE("examples/rig_history_fit.rheo: a preloaded rig history with a load-cell offset gives back its model and the offset") {
  const fs::path fitted = scratch() / "rig_fitted.rheo", json_path = scratch() / "rig.json";
  REQUIRE(rheo_run(fmt::format("fit {} --json -o {} > {}", example("rig_history_fit.rheo"), fitted.string(), json_path.string())) == 0);
  std::ifstream in(json_path);
  const auto summary = nlohmann::json::parse(in);
  const std::map<std::string, double> truth{{"rubber.D10", 389.43}, {"rubber.D20", -2.1094}, {"rubber.D30", 0.0786},
                                            {"m1.k", 61.476},       {"m1.tau", 4.335},       {"f1.k", 1016.6},
                                            {"f1.uy", 101.58},      {"f2.k", 301.04},        {"f2.uy", 42.256}};
  int checked = 0;
  for (const auto& p : summary.at("parameters")) {
    if (!p.at("free").get<bool>()) continue;  // derived ones (m1.c, f1.fy) follow
    ++checked;
    CAPTURE(p.at("path").get<std::string>());
    // The file's load is rounded to 10 mN: the Maxwell arm (a few N of the ~1.6 kN) is the least determined.
    CHECK(std::abs(p.at("value").get<double>() / truth.at(p.at("path").get<std::string>()) - 1.0) < 2e-3);
  }
  CHECK(checked == 9);
  const auto& offset = summary.at("data").at(0).at("force_offset");
  CHECK(offset.at("value").get<double>() == doctest::Approx(150.0).epsilon(1e-4));
  CHECK(summary.at("err").get<double>() < 1e-5);
  CHECK(rheo_run(fmt::format("check {}", fitted.string())) == 0);
}

// The friction damper rig file (examples/data/README.md): refine names the free play, then the
// one-sided yield, and the gap falls from 45 times the noise put in to near it (the drifting
// zero adds a little); the final model checks. Two rounds: a third only confirms `none`.
TEST_CASE("examples/friction_damper_refine.rheo: refine names backlash, then asymmetry, and reaches the noise") {
  const fs::path dir = scratch();
  const fs::path refined = dir / "damper_refined.rheo", out = dir / "refine.txt";
  REQUIRE(rheo_run(fmt::format("refine {} --rounds 2 -o {} > {} 2> /dev/null", example("friction_damper_refine.rheo"), refined.string(),
                               out.string())) == 0);
  std::ifstream in(out);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  MESSAGE(text);
  const std::size_t first = text.find("round 1:"), second = text.find("round 2:");
  REQUIRE(first != std::string::npos);
  REQUIRE(second != std::string::npos);
  CHECK(text.find("effect backlash", first) < second);
  CHECK(text.find("effect asymmetry", second) != std::string::npos);
  const runtime::Table table = runtime::read_table(data("friction_damper_rig.csv"));
  double largest = 0.0;
  for (double f : table.columns[2]) largest = std::max(largest, std::abs(f));
  double after = 0.0;  // the round's "BEFORE -> AFTER"
  REQUIRE(std::sscanf(text.c_str() + text.find("->", second), "-> %lf", &after) == 1);
  CHECK(after < 1.4 * 60.0 / largest);  // 60 N of noise in the file
  CHECK(rheo_run(fmt::format("check {} > /dev/null", refined.string())) == 0);
}

}  // namespace examples_fit_test
