// The binary's exit codes and messages (docs/cli.md): 0 ok, 2 usage, 3 model, 4 data.
#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace cli_test {

namespace fs = std::filesystem;

namespace {

struct Result {
  int code;
  std::string output;  // stdout and stderr
};

Result run(const std::string& arguments) {
  const std::string command = fmt::format("{} {} 2>&1", RHEO_BINARY, arguments);
  Result r{-1, ""};
  FILE* pipe = popen(command.c_str(), "r");
  std::array<char, 4096> buffer{};
  while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) r.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

fs::path write(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("rheo-cli-{}", ::getpid());
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}

}  // namespace

TEST_CASE("check: a valid file exits 0, an invalid one 3 with file:line:col and a caret") {
  CHECK(run(fmt::format("check {}/bushing_d.rheo", RHEO_EXAMPLES_DIR)).code == 0);
  const auto bad = write("bad.rheo", "model m {\n  spring s (k = 5 mm)\n}\n");
  const Result r = run("check " + bad.string());
  CHECK(r.code == 3);
  CHECK(r.output.find("bad.rheo:2:") != std::string::npos);
  CHECK(r.output.find("stiffness") != std::string::npos);
  CHECK(r.output.find('^') != std::string::npos);
}

TEST_CASE("a network that cannot be simulated exits 3 from check and simulate, naming the element, and check prints no ok") {
  const auto bad = write("gap.rheo",
                         "model m {\n  spring s (k = 5 N/mm)\n  gap play (width = 0.2 mm)\n}\n"
                         "simulate { harmonic frequency = 1 Hz, amplitude = 0.1 mm }\n");
  const Result check = run("check " + bad.string());
  CHECK(check.code == 3);
  CHECK(check.output.find("gap.rheo:3:3: error: model 'm': gap 'play'") != std::string::npos);
  CHECK(check.output.find("'play'") != std::string::npos);
  CHECK(check.output.find(": ok:") == std::string::npos);
  const Result simulate = run("simulate " + bad.string());
  CHECK(simulate.code == 3);
  CHECK(simulate.output.find("'play'") != std::string::npos);
}

TEST_CASE("check raises the integrator's errors exactly where a run of the file would meet them") {
  // An inerter between the terminal and ground: IDA cannot integrate it (it needs the drive's
  // acceleration), the fixed-step kernels and the harmonic closed form can.
  const std::string model = "model m {\n  spring s (k = 100 N/mm)\n  inerter i (b = 1 kg)\n}\n";
  for (const auto& [protocol, fails] : {std::pair{"static velocity = 1 mm/s, amplitude = 1 mm", true},
                                        std::pair{"harmonic frequency = 1 Hz, amplitude = 1 mm, steady_state = time_stepping", true},
                                        std::pair{"harmonic frequency = 1 Hz, amplitude = 1 mm", false},
                                        std::pair{"static velocity = 1 mm/s, amplitude = 1 mm, solver = fixed", false}}) {
    const std::string line = protocol;
    CAPTURE(line);
    const auto file = write("inerter.rheo", model + "simulate { " + protocol + " }\n");
    const Result check = run("check " + file.string());
    const Result simulate = run("simulate " + file.string() + " -o /dev/null");
    CHECK(check.code == (fails ? 3 : 0));
    CHECK(simulate.code == check.code);
    if (fails)
      CHECK(check.output.find("inerter.rheo:3:3: error: inerter 'i' of model 'm' sits directly between the terminal and ground") != std::string::npos);
  }
}

TEST_CASE("usage errors exit 2 and say what to do") {
  CHECK(run("").code == 2);
  CHECK(run("simulate").code == 2);
  const auto no_sim = write("nosim.rheo", "model m { spring s (k = 5) }\n");
  const Result r = run("simulate " + no_sim.string());
  CHECK(r.code == 2);
  CHECK(r.output.find("no simulate block") != std::string::npos);
  const Result bad_set = run(fmt::format("simulate {}/bushing_d.rheo -o - --set 'frequency = 5 mm'", RHEO_EXAMPLES_DIR));
  CHECK(bad_set.code == 2);
  CHECK(bad_set.output.find("frequency") != std::string::npos);
}

TEST_CASE("simulate with overrides writes to standard output") {
  const Result r = run(fmt::format("simulate {}/bushing_d.rheo -o - --set 'frequency = [5, 10] Hz' --set 'amplitude = 0.2 mm'", RHEO_EXAMPLES_DIR));
  CHECK(r.code == 0);
  CHECK(r.output.find("amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]") != std::string::npos);
  CHECK(r.output.find("\n0.2,10,") != std::string::npos);
}

TEST_CASE("data errors exit 4 and leave no output") {
  const auto history = write("h.csv", "time [s],displacement [mm]\n0,0\n0.1,oops\n");
  const auto model = write(
      "h.rheo", fmt::format("model m {{ spring s (k = 5) }}\nsimulate {{ history file = \"{}\"\n output \"h_out.csv\" }}\n", history.string()));
  const Result r = run("simulate " + model.string());
  CHECK(r.code == 4);
  CHECK(r.output.find("h.csv:3:5: error:") != std::string::npos);
  CHECK_FALSE(fs::exists(model.parent_path() / "h_out.csv"));
  // A later protocol's bad data leaves the earlier protocol's existing output as it was.
  const auto earlier = write("first_out.csv", "earlier result\n");
  const auto two = write("two.rheo", fmt::format("model m {{ spring s (k = 5) }}\nsimulate {{\n harmonic frequency = 1 Hz, amplitude = 1 mm\n"
                                                 " output \"first_out.csv\"\n history file = \"{}\"\n output \"h_out.csv\" }}\n",
                                                 history.string()));
  CHECK(run("simulate " + two.string()).code == 4);
  std::ifstream kept(earlier);
  std::string line;
  std::getline(kept, line);
  CHECK(line == "earlier result");
  // So does a later protocol's, or the report's, unwritable destination: found before anything runs.
  const auto bad_path = write("bad_path.rheo",
                              "model m { spring s (k = 5) }\nsimulate {\n harmonic frequency = 1 Hz, amplitude = 1 mm\n"
                              " output \"first_out.csv\"\n step amplitude = 1 mm, duration = 1 s\n output \"no_dir/x.csv\" }\n");
  const Result path_run = run("simulate " + bad_path.string());
  CHECK(path_run.code == 4);
  CHECK(path_run.output.find("no_dir does not exist; create it or choose another path") != std::string::npos);
  const Result report_run = run("simulate " + two.string() + " --protocol harmonic --report " +
                                (earlier.parent_path() / "no_dir" / "r.html").string());
  CHECK(report_run.code == 4);
  CHECK(report_run.output.find("r.html: error: the output's directory") != std::string::npos);
  std::ifstream still(earlier);
  std::getline(still, line);
  CHECK(line == "earlier result");
}

TEST_CASE("a history from a preloaded displacement starts relaxed there, start = rest refuses it at the cell") {
  const auto history = write("preloaded.csv", "time [s],displacement [mm]\n0,2\n0.5,2.5\n");
  const auto model = write("preloaded.rheo", fmt::format("model m {{ spring s (k = 5 N/mm)\n friction f (k = 10 N/mm, fy = 1 N) }}\n"
                                                         "simulate {{ history file = \"{}\" }}\n",
                                                         history.string()));
  const Result relaxed = run("simulate " + model.string() + " -o -");
  CHECK(relaxed.code == 0);
  CHECK(relaxed.output.find("\n0,2,10\n") != std::string::npos);        // the spring's 5 N/mm x 2 mm; the friction element slid to 0
  CHECK(relaxed.output.find("\n0.5,2.5,13.5\n") != std::string::npos);  // 12.5 N + the friction element's fy
  const Result rest = run("simulate " + model.string() + " -o - --set 'start = rest'");
  CHECK(rest.code == 4);
  CHECK(rest.output.find("preloaded.csv:2:3: error: with start = rest the history must start from rest") != std::string::npos);
}

TEST_CASE("simulate --threads gives the same file as one thread, a negative count is a usage error") {
  const std::string base = fmt::format("simulate {}/hydromount.rheo -o - --set 'steps_per_cycle = 256' --protocol harmonic", RHEO_EXAMPLES_DIR);
  const Result one = run(base);
  const Result two = run(base + " --threads 2");
  CHECK(one.code == 0);
  CHECK(two.code == 0);
  CHECK(one.output.find("amplitude [mm]") != std::string::npos);
  CHECK(two.output == one.output);
  CHECK(run(base + " --threads -1").code == 2);
}

TEST_CASE("fit --threads 2 writes the fitted model and the summary of one thread: same parameters, err and evaluations") {
  // Specimen D's default fit: Jacobian columns and samples side by side on two threads.
  auto fitted = [](int threads) {
    const fs::path model = write(fmt::format("specimen_d_fitted_{}.rheo", threads), "");
    const Result r = run(fmt::format("fit {}/specimen_d_fit.rheo --threads {} --json -o {}", RHEO_EXAMPLES_DIR, threads, model.string()));
    REQUIRE(r.code == 0);
    const std::size_t begin = r.output.find("\n{") + 1;  // after the line naming the file written
    nlohmann::json summary = nlohmann::json::parse(r.output.substr(begin, r.output.rfind('}') + 1 - begin));
    summary.erase("wall_seconds");
    std::ifstream in(model);
    return std::pair{summary, std::string(std::istreambuf_iterator<char>(in), {})};
  };
  const auto [one, one_model] = fitted(1);
  const auto [two, two_model] = fitted(2);
  CHECK(one.at("evaluations").get<int>() > 100);
  CHECK(two.at("evaluations") == one.at("evaluations"));
  CHECK(two.at("err") == one.at("err"));
  CHECK(two.at("parameters") == one.at("parameters"));
  CHECK(two == one);
  CHECK(one_model.find("model specimen_d") != std::string::npos);
  CHECK(two_model == one_model);
}

TEST_CASE("a model file that cannot be read exits 4 naming it, for every command") {
  for (const char* command : {"check", "simulate", "fit"}) {
    CAPTURE(command);
    const Result missing = run(fmt::format("{} /nonexistent/model.rheo", command));
    CHECK(missing.code == 4);
    CHECK(missing.output.find("/nonexistent/model.rheo: error: cannot read it (No such file or directory)") == 0);
    const Result directory = run(fmt::format("{} {}", command, RHEO_EXAMPLES_DIR));
    CHECK(directory.code == 4);
    CHECK(directory.output.find("cannot read it (it is a directory)") != std::string::npos);
  }
}

TEST_CASE("--version prints the version of project(VERSION) in CMakeLists.txt") {
  const Result r = run("--version");
  CHECK(r.code == 0);
  CHECK(r.output == fmt::format("rheo {}\n", RHEO_PROJECT_VERSION));
}

}  // namespace cli_test
