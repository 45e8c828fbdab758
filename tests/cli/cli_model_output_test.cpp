// Model files written elsewhere than their source (cli/model_output.cpp, #22 item 2): `rheo fit
// -o`, `diagnose -o` and `refine -o` into another folder write data lines that still name the
// same files, so the written file fits and checks from there; `rheo check` warns of a data file
// that does not exist and still exits 0.
#include "cli_support.hpp"
#include "support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace cli_model_output_test {

namespace fs = std::filesystem;
using rheo::test::run_rheo;

namespace {

fs::path scratch() { return rheo::test::scratch_directory("cli-model-output"); }
std::string read_text(const fs::path& path) { return rheo::test::read_file(path.string()); }
auto run(const std::string& arguments) { return run_rheo(arguments); }

// The data lines of a .rheo text.
std::vector<std::string> data_names(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (const auto at = line.find("data \""); at != std::string::npos && line.find('#') > at) {
      const auto begin = at + 6;
      out.push_back(line.substr(begin, line.find('"', begin) - begin));
    }
  return out;
}

}  // namespace

TEST_CASE("fit -o into another folder: the data lines name the same files, and the written file fits from there") {
  // A source and its data in one folder, the output two folders away.
  const fs::path home = scratch() / "home", away = scratch() / "away" / "deeper";
  fs::create_directories(home / "data");
  fs::create_directories(away);
  fs::copy_file(fmt::format("{}/hydrobushing_harmonic.csv", RHEO_DATA_DIR), home / "data" / "h.csv", fs::copy_options::overwrite_existing);
  std::ofstream(home / "m.rheo") << "model m {\n  spring k (k = 500 N/mm in [10, 10000])\n  maxwell m1 (k = 100 N/mm in [1, 10000], tau = 5 ms in [0.1, 100])\n}\n"
                                    "fit m {\n  data \"data/h.csv\"\n  data \"" +
                                        (home / "data" / "h.csv").string() + "\", weight = 0.5\n}\n";
  const fs::path out = away / "fitted.rheo";
  const auto r = run(fmt::format("fit {} -o {}", (home / "m.rheo").string(), out.string()));
  REQUIRE(r.code == 0);
  const auto names = data_names(read_text(out));
  REQUIRE(names.size() == 2);
  CHECK(names[0] == "../../home/data/h.csv");             // relative, from the output's folder
  CHECK(names[1] == (home / "data" / "h.csv").string());  // absolute names are kept
  CHECK(fs::equivalent(out.parent_path() / names[0], home / "data" / "h.csv"));
  CHECK(run("check " + out.string()).err.find("warning") == std::string::npos);
  CHECK(run("fit " + out.string()).code == 0);
  // Into the source's own folder nothing changes.
  const fs::path beside = home / "fitted.rheo";
  REQUIRE(run(fmt::format("fit {} -o {}", (home / "m.rheo").string(), beside.string())).code == 0);
  CHECK(data_names(read_text(beside))[0] == "data/h.csv");
}

TEST_CASE("check warns of a data file that does not exist, naming where, and exits 0") {
  const fs::path file = scratch() / "missing.rheo";
  std::ofstream(file) << "model m { spring k (k = 1 N/mm in [0.1, 10]) }\nfit m {\n  data \"nowhere/h.csv\"\n}\n";
  const auto r = run("check " + file.string());
  CHECK(r.code == 0);
  CHECK(r.err.find(fmt::format("{}:3:8: warning: data file 'nowhere/h.csv' does not exist", file.string())) != std::string::npos);
}

}  // namespace cli_model_output_test
