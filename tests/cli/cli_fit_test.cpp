// `rheo fit` through the real binary (cli/fit_command.cpp, fit_job.cpp, order_study.cpp):
// the fitted file reproduces the reported fit, keeps the source's comments and is written even
// when Ctrl-C stops the search; data errors name file:row:col and leave earlier outputs intact;
// usage errors say what to give; the yeoh start, the order study and the three methods of
// issue #3 end where their definitions say.
#include "lang/frontend.hpp"
#include "runtime/io/fit_data.hpp"
#include "runtime/fit/fit_scoring.hpp"
#include "runtime/fit/objective.hpp"
#include "runtime/fit/yeoh_mean_curve.hpp"

#include <doctest/doctest.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

namespace cli_fit_test {

using namespace rheo;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

struct Run {
  int code;
  std::string out, err;
};

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / fmt::format("rheo-cli-fit-{}", ::getpid());
  fs::create_directories(dir);
  return dir;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_text(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

Run run(const std::string& arguments) {
  const fs::path err = scratch() / "stderr.txt";
  const std::string command = fmt::format("{} {} 2> {}", RHEO_BINARY, arguments, err.string());
  Run r{-1, "", ""};
  FILE* pipe = popen(command.c_str(), "r");
  std::array<char, 4096> buffer{};
  while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) r.out.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = read_text(err);
  return r;
}

std::string example(const std::string& name) { return fmt::format("{}/{}", RHEO_EXAMPLES_DIR, name); }
std::string data(const std::string& name) { return fmt::format("{}/{}", RHEO_DATA_DIR, name); }

// err (6.1) of FILE's model on the harmonic data, by compiling FILE anew: an independent path
// from the report's to the fitted values.
double err_of_file(const fs::path& file, const std::string& model, const std::string& data_path) {
  const lang::Program program = lang::load_program(file.string());
  const lang::CheckedModel* checked = program.find_model(model);
  REQUIRE(checked != nullptr);
  const runtime::Network network = runtime::Network::compile(*checked);
  const runtime::FitDataSet set = runtime::read_fit_data(data_path, 1.0);
  const auto points = runtime::predict(network, set, runtime::FitMethod::exact, {}, nullptr).points;
  return runtime::thesis_err(runtime::relative_residuals(set.harmonic(), points));
}

// Noise-free harmonic data of a spring + Maxwell + friction model, written by `rheo simulate`.
fs::path truth_data() {
  const fs::path csv = scratch() / "truth.csv";
  if (fs::exists(csv)) return csv;
  const fs::path model = scratch() / "truth.rheo";
  write_text(model,
             "model t {\n  spring e (k = 100 N/mm)\n  maxwell m (k = 50 N/mm, tau = 10 ms)\n  friction f (k = 200 N/mm, uy = 50 um)\n}\n"
             "simulate {\n  harmonic frequency = [1, 5, 20, 50] Hz, amplitude = [0.02, 0.05, 0.1, 0.3, 1.0] mm\n"
             "  output \"truth.csv\"\n}\n");
  REQUIRE(run("simulate " + model.string()).code == 0);
  return csv;
}

// The truth's structure with generic start values and bounds; no fit block.
fs::path start_model() {
  const fs::path file = scratch() / "start.rheo";
  write_text(file,
             "# generic start\nmodel t {\n  spring e (k = 300 N/mm in [1, 10000])\n"
             "  maxwell m (k = 100 N/mm in [1, 10000], tau = 3 ms in [0.01, 10000])\n"
             "  friction f (k = 100 N/mm in [1, 10000], uy = 20 um in [0.1, 10000])\n}\n");
  return file;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The '#' comment lines of a source, in order.
std::vector<std::string> comment_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.find('#') != std::string::npos) lines.push_back(line.substr(line.find('#')));
  return lines;
}

}  // namespace

TEST_CASE("parsing and simulating the fitted file reproduces the reported fit, the file keeps the source's comments") {
  const fs::path out = scratch() / "specimen_d_fitted.rheo";
  const Run r = run(fmt::format("fit {} -o {} --json", example("specimen_d_fit.rheo"), out.string()));
  REQUIRE(r.code == 0);
  CHECK(contains(r.err, "written to " + out.string()));
  const json report = json::parse(r.out);
  CHECK(report["interrupted"] == false);
  const double reported = report["err"].get<double>();
  const double recomputed = err_of_file(out, "specimen_d", data("specimen_D_harmonic.csv"));
  CAPTURE(reported);
  CAPTURE(recomputed);
  CHECK(std::abs(recomputed / reported - 1.0) < 1e-9);
  // Every comment of the source is still there, in order, after the header the fit adds.
  const std::string fitted = read_text(out);
  CHECK(fitted.rfind("# Fitted by `rheo fit` (method exact, objective phi) to:", 0) == 0);
  const auto source_comments = comment_lines(read_text(example("specimen_d_fit.rheo")));
  const auto fitted_comments = comment_lines(fitted);
  REQUIRE(fitted_comments.size() >= source_comments.size());
  CHECK(std::equal(source_comments.begin(), source_comments.end(), fitted_comments.end() - static_cast<long>(source_comments.size())));
  // The data line names the same file from the output's folder (cli_model_output_test).
  CHECK(contains(
      fitted, "fit {\n  data \"" +
                  fs::path(data("specimen_D_harmonic.csv")).lexically_normal().lexically_relative(fs::absolute(out.parent_path())).generic_string() +
                  "\""));
}

TEST_CASE("a file without a fit block is fitted to --data, without --data it exits 2 and says to give it") {
  const Run r = run(fmt::format("fit {} --data {} --json", start_model().string(), truth_data().string()));
  REQUIRE(r.code == 0);
  const json report = json::parse(r.out);
  CHECK(report["err"].get<double>() < 1e-6);
  CHECK(report["data"][0]["file"] == truth_data().string());
  const Run missing = run("fit " + start_model().string());
  CHECK(missing.code == 2);
  CHECK(contains(missing.err, "no data to fit model 't'"));
  CHECK(contains(missing.err, "give --data FILE.csv"));
  CHECK(missing.out.empty());
}

TEST_CASE("a model the fit's solver cannot simulate exits 3 naming the element, as from simulate") {
  const fs::path model = scratch() / "inerter_root.rheo";
  write_text(model, "model m { spring s (k = 100 N/mm in [1, 1000]) inerter b (b = 0.001 N*s^2/mm) }\nfit { solver = sundials }\n");
  const Run r = run(fmt::format("fit {} --data {}", model.string(), truth_data().string()));
  CHECK(r.code == 3);
  CHECK(contains(r.err, "inerter_root.rheo:1:48: error: inerter 'b' of model 'm' sits directly between the terminal and ground"));
  CHECK(contains(r.err, "or use solver = fixed"));
}

TEST_CASE("an output that cannot be written exits 4 before the search, with advice") {
  const Run missing_dir = run(
      fmt::format("fit {} --data {} -o {} --json", start_model().string(), truth_data().string(), (scratch() / "no_such_dir" / "x.rheo").string()));
  CHECK(missing_dir.code == 4);
  CHECK(contains(missing_dir.err, "no_such_dir does not exist; create it or choose another path"));
  CHECK(missing_dir.out.empty());  // no report: the fit never ran
  const Run directory = run(fmt::format("fit {} --data {} -o {}", start_model().string(), truth_data().string(), scratch().string()));
  CHECK(directory.code == 4);
  CHECK(contains(directory.err, "the output is a directory; name a file in it"));
  // The --report and --plot files too, before the search (no "fitted model written" line).
  for (const char* option : {"--report", "--plot"}) {
    CAPTURE(option);
    const Run report = run(fmt::format("fit {} --data {} -o {} {} {}", start_model().string(), truth_data().string(),
                                       (scratch() / "ok.rheo").string(), option, (scratch() / "no_such_dir" / "r.html").string()));
    CHECK(report.code == 4);
    CHECK(contains(report.err, "no_such_dir does not exist; create it or choose another path"));
    CHECK(!contains(report.err, "written"));
  }
}

TEST_CASE("bad data exits 4 naming file:row:col, and leaves an existing output untouched") {
  const std::string good = read_text(data("specimen_D_harmonic.csv"));
  std::vector<std::string> lines;
  std::istringstream in(good);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  REQUIRE(lines.size() > 6);
  REQUIRE(lines[1].rfind("amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]", 0) == 0);
  auto with_line = [&](std::size_t index, const std::string& replacement) {
    auto copy = lines;
    copy[index] = replacement;
    std::string text;
    for (const auto& l : copy) text += l + "\n";
    return text;
  };
  const std::string row5 = lines[4];  // file line 5: "0.200,5.00,1416.8583,18.0715"
  const auto comma1 = row5.find(','), comma2 = row5.find(',', comma1 + 1), comma3 = row5.find(',', comma2 + 1);
  struct Case {
    const char* name;
    std::string text;
    std::string where;  // file:row:col
    const char* what;
  };
  const Case cases[] = {
      {"non_number.csv", with_line(4, row5.substr(0, comma2 + 1) + "14x6.8" + row5.substr(comma3)), fmt::format(":5:{}:", comma2 + 2),
       "'14x6.8' is not a number (column 'stiffness')"},
      {"missing_value.csv", with_line(4, row5.substr(0, comma3)), ":5:1:", "this row has 3 values, the header has 4 columns"},
      {"negative_amplitude.csv", with_line(5, "-" + lines[5]), ":6:1:", "amplitude must be positive"},
  };
  const fs::path out = scratch() / "kept.rheo";
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const fs::path csv = scratch() / c.name;
    write_text(csv, c.text);
    write_text(out, "# an earlier result\n");
    const Run r = run(fmt::format("fit {} --data {} -o {}", example("specimen_d_fit.rheo"), csv.string(), out.string()));
    CAPTURE(r.err);
    CHECK(r.code == 4);
    CHECK(r.err.rfind(csv.string() + c.where + " error: ", 0) == 0);
    CHECK(contains(r.err, c.what));
    CHECK(read_text(out) == "# an earlier result\n");
  }
  // A table without a needed column names the file and the column.
  const fs::path no_phase = scratch() / "no_phase.csv";
  write_text(no_phase, "amplitude [mm],frequency [Hz],stiffness [N/mm]\n0.2,1,1419\n");
  const Run r = run(fmt::format("fit {} --data {} -o {}", example("specimen_d_fit.rheo"), no_phase.string(), out.string()));
  CHECK(r.code == 4);
  CHECK(r.err.rfind(no_phase.string() + ":1:1: error: ", 0) == 0);
  CHECK(contains(r.err, "'phase'"));
  CHECK(read_text(out) == "# an earlier result\n");
}

TEST_CASE("Ctrl-C stops the fit with exit code 130, writes the best result so far and says it was interrupted") {
  const fs::path out = scratch() / "interrupted.rheo", report = scratch() / "interrupted.json", messages = scratch() / "interrupted.err";
  fs::remove(out);
  // Many local searches: the run takes far longer than the wait below, whatever the machine.
  const std::vector<std::string> arguments{
      RHEO_BINARY, "fit", example("specimen_d_fit.rheo"), "-o", out.string(), "--max-evaluations", "1000000", "--starts", "100", "--json"};
  std::vector<char*> argv;
  for (const auto& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const std::string report_path = report.string(), messages_path = messages.string();
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    ::dup2(::open(report_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644), STDOUT_FILENO);
    ::dup2(::open(messages_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644), STDERR_FILENO);
    ::execv(RHEO_BINARY, argv.data());
    ::_exit(127);
  }
  // Wait until the fit has installed its SIGINT handler (SigCgt in /proc), then let it search.
  auto handles_sigint = [&] {
    std::ifstream status(fmt::format("/proc/{}/status", pid));
    for (std::string line; std::getline(status, line);)
      if (line.rfind("SigCgt:", 0) == 0) return ((std::stoull(line.substr(7), nullptr, 16) >> (SIGINT - 1)) & 1ULL) != 0;
    return false;
  };
  int status = 0;
  bool exited = false;
  for (int i = 0; i < 3000 && !handles_sigint(); ++i) {
    if (::waitpid(pid, &status, WNOHANG) == pid) {
      exited = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  REQUIRE_FALSE(exited);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ::kill(pid, SIGINT);
  for (int i = 0; i < 6000 && !exited; ++i) {
    exited = ::waitpid(pid, &status, WNOHANG) == pid;
    if (!exited) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!exited) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    FAIL("rheo fit did not stop within 60 s of SIGINT");
  }
  CAPTURE(read_text(messages));
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  const json j = json::parse(read_text(report));
  CHECK(j["interrupted"] == true);
  CHECK(j["status"] == "interrupted");
  REQUIRE(fs::exists(out));
  CHECK(contains(read_text(out), "# Interrupted: the best values found before the interruption."));
  const double recomputed = err_of_file(out, "specimen_d", data("specimen_D_harmonic.csv"));
  CHECK(std::abs(recomputed / j["err"].get<double>() - 1.0) < 1e-9);
}

TEST_CASE("--yeoh-start writes the least-squares constants of the static loop's mean curve (eqs. 5.28-5.32)") {
  const fs::path out = scratch() / "yeoh_started.rheo";
  const Run r = run(
      fmt::format("fit {} --yeoh-start {} --max-evaluations 1 -o {}", example("specimen_d_fit.rheo"), data("specimen_D_static.csv"), out.string()));
  REQUIRE(r.code == 0);
  CHECK(contains(r.err, "rubber.D10 = "));
  const runtime::YeohConstants want = runtime::fit_yeoh_least_squares(
      runtime::mean_curve(runtime::largest_loop(runtime::loop_samples_from_table(runtime::read_table(data("specimen_D_static.csv"))))));
  const lang::Program program = lang::load_program(out.string());
  const lang::CheckedModel* model = program.find_model("specimen_d");
  REQUIRE(model != nullptr);
  const std::pair<const char*, double> expected[] = {{"rubber.D10", want.d10}, {"rubber.D20", want.d20}, {"rubber.D30", want.d30}};
  for (const auto& entry : expected) {  // not a structured binding: Clang 14 cannot capture one
    const std::string path = entry.first;
    const double value = entry.second;
    CAPTURE(path);
    const auto p = std::find_if(model->parameters.begin(), model->parameters.end(), [&](const auto& q) { return q.path == path; });
    REQUIRE(p != model->parameters.end());
    CHECK(std::abs(p->value / value - 1.0) < 1e-9);
  }
}

TEST_CASE("--yeoh-start on a record without a full cycle names the file and what it needs (exit 4, nothing written)") {
  const fs::path ramp = scratch() / "ramp.csv", out = scratch() / "ramp_started.rheo";
  write_text(ramp, "time [s],displacement [mm],force [N]\n0,0,0\n1,0.5,100\n2,1,210\n3,1.5,330\n");
  fs::remove(out);
  const Run r = run(fmt::format("fit {} --yeoh-start {} --max-evaluations 1 -o {}", example("specimen_d_fit.rheo"), ramp.string(), out.string()));
  CHECK(r.code == 4);
  CHECK(contains(r.err, ramp.string() + ": --yeoh-start: largest_loop: the record holds no full cycle"));
  CHECK(contains(r.err, "give a static loop record"));
  CHECK(!fs::exists(out));
}

TEST_CASE("--yeoh-start leaves fixed yeoh constants as written, so the fitted file still reproduces the fit") {
  // specimen_d_methods.rheo's model: D20 and D30 without bounds (fixed), D10 free.
  const std::string source = read_text(example("specimen_d_methods.rheo"));
  const fs::path file = scratch() / "fixed_shape.rheo", out = scratch() / "fixed_shape_fitted.rheo";
  write_text(file, source.substr(0, source.find("fit {")) + fmt::format("fit {{\n  data \"{}\"\n}}\n", data("specimen_D_harmonic.csv")));
  const Run r = run(
      fmt::format("fit {} --yeoh-start {} --max-evaluations 1 -o {} --json", file.string(), data("specimen_D_static.csv"), out.string()));
  REQUIRE(r.code == 0);
  CHECK(contains(r.err, "rubber.D20 is not free and keeps its value"));
  CHECK(contains(read_text(out), "D20 = -2.1094 N/mm^3, D30 = 0.0786 N/mm^5)"));
  const double reported = json::parse(r.out)["err"].get<double>();
  CHECK(std::abs(err_of_file(out, "specimen_d", data("specimen_D_harmonic.csv")) / reported - 1.0) < 1e-9);
}

TEST_CASE("--orders fits every structure and tables err, the true structure fits noise-free data exactly") {
  const std::string arguments = fmt::format("fit {} --data {} --orders maxwell=1..2,friction=1..2", start_model().string(), truth_data().string());
  const Run text = run(arguments);
  REQUIRE(text.code == 0);
  int rows = 0;
  std::istringstream in(text.out);
  for (std::string line; std::getline(in, line);) {
    int m = 0, f = 0, n = 0;
    double err = 0.0, seconds = 0.0;
    if (std::sscanf(line.c_str(), "%d %d %d %lf %lf", &m, &f, &n, &err, &seconds) == 5) ++rows;
  }
  CHECK(rows == 4);
  const Run j = run(arguments + " --json");
  REQUIRE(j.code == 0);
  const json table = json::parse(j.out);
  REQUIRE(table.size() == 4);
  for (const json& row : table) {
    REQUIRE(row.contains("err"));
    CHECK(row["parameters"] == 1 + 2 * row["maxwell"].get<int>() + 2 * row["friction"].get<int>());
    if (row["maxwell"] == 1 && row["friction"] == 1) CHECK(row["err"].get<double>() < 1e-6);
  }
}

TEST_CASE("--orders warm-starts each structure from the one with an element fewer (err falls) and -o writes the chosen one") {
  const fs::path out = scratch() / "orders_chosen.rheo";
  const Run r = run(fmt::format("fit {} --data {} --orders maxwell=1..2,friction=1..3 --max-evaluations 400 --json -o {}", start_model().string(),
                                data("specimen_D_harmonic.csv"), out.string()));
  REQUIRE(r.code == 0);
  const json table = json::parse(r.out);
  REQUIRE(table.size() == 6);
  std::map<std::pair<int, int>, double> err;
  for (const json& row : table) err[{row["maxwell"].get<int>(), row["friction"].get<int>()}] = row["err"].get<double>();
  for (int m = 1; m <= 2; ++m)
    for (int f = 1; f <= 3; ++f) {
      CAPTURE(m);
      CAPTURE(f);
      if (f > 1) CHECK(err[{m, f}] <= err[{m, f - 1}] * (1.0 + 1e-6));
      if (m > 1 && f == 1) CHECK(err[{m, f}] <= err[{m - 1, f}] * (1.0 + 1e-6));  // a row starts from the row above
    }
  REQUIRE(contains(r.err, "written to " + out.string()));
  const std::string written = read_text(out);
  CHECK(contains(written, "Chosen by `rheo fit --orders` among 6 structures"));
  // The file is the chosen structure with its fitted values: compiled anew, its err is a row's.
  const double recomputed = err_of_file(out, "t", data("specimen_D_harmonic.csv"));
  CHECK(std::any_of(err.begin(), err.end(), [&](const auto& e) { return std::abs(recomputed / e.second - 1.0) < 1e-6; }));
}

TEST_CASE("specimen D by the three methods: the exact method's err is the lowest (issue #3 acceptance)") {
  const Run r = run(fmt::format("fit {} --json", example("specimen_d_methods.rheo")));
  REQUIRE(r.code == 0);
  const json results = json::parse(r.out);
  REQUIRE(results.size() == 3);
  std::map<std::string, double> err;
  for (const json& result : results) err[result["method"].get<std::string>()] = result["err"].get<double>();
  REQUIRE(err.size() == 3);
  CAPTURE(err["exact"]);
  CAPTURE(err["approximate"]);
  CAPTURE(err["corrected"]);
  CHECK(err["exact"] <= err["corrected"]);
  CHECK(err["exact"] < err["approximate"]);
}

TEST_CASE("the approximate and corrected methods on a nested model exit 2 naming the element and the method to use") {
  // A spring and a dashpot alone in series would be a Maxwell element; the slider makes it a subtree.
  const fs::path nested = scratch() / "nested.rheo";
  write_text(nested,
             "model n {\n  spring e (k = 100 N/mm in [1, 1000])\n  series arm {\n    spring s (k = 50 N/mm in [1, 1000])\n"
             "    dashpot d (c = 0.5 N*s/mm in [0.01, 10])\n    slider cap (fy = 10 N)\n  }\n}\n");
  for (const std::string method : {"approximate", "corrected"}) {
    CAPTURE(method);
    const Run r = run(fmt::format("fit {} --data {} --method {}", nested.string(), truth_data().string(), method));
    CHECK(r.code == 2);
    CHECK(contains(r.err, "cannot fit model 'n': spring 'arm.s'"));
    CHECK(contains(r.err, "use method = exact"));
  }
}

TEST_CASE("command-line mistakes exit 2 and name the option") {
  const std::string base = fmt::format("fit {} --data {}", start_model().string(), truth_data().string());
  const Run method = run(base + " --method fastest");
  CHECK(method.code == 2);
  CHECK(contains(method.err, "unknown method 'fastest'; use exact, approximate or corrected"));
  const Run optimizer = run(base + " --optimizer newton");
  CHECK(optimizer.code == 2);
  CHECK(contains(optimizer.err, "unknown optimizer 'newton'"));
  const Run budget = run(base + " --max-evaluations 0");
  CHECK(budget.code == 2);
  CHECK(contains(budget.err, "--max-evaluations"));
  const Run several = run(fmt::format("fit {} -o {}", example("specimen_d_methods.rheo"), (scratch() / "x.rheo").string()));
  CHECK(several.code == 2);
  CHECK(contains(several.err, "3 fits would run"));
  CHECK_FALSE(fs::exists(scratch() / "x.rheo"));
  const Run beyond = run(fmt::format("fit {} --block 4", example("specimen_d_methods.rheo")));
  CHECK(beyond.code == 2);
  CHECK(contains(beyond.err, "--block 4: "));
  CHECK(contains(beyond.err, "has 3 fit block(s)"));
  for (const std::string duration : {"soon", "5 parsecs", "-3s", "0", "10 mm"}) {
    CAPTURE(duration);
    const Run limit = run(base + " --time-limit '" + duration + "'");
    CHECK(limit.code == 2);
    CHECK(contains(limit.err, "--time-limit '" + duration + "': give a positive duration, e.g. 60s, 90 s or 5 min"));
  }
}

TEST_CASE("--time-limit (or the block's time_limit) stops the search in time and reports the best values found so far") {
  // The coupled bushing's fit from its generic start takes about 500 evaluations (0.25 s on an
  // idle 2-core machine, 2026-11-27) within a limit it can meet, more unbounded; a limit of 0.05 s
  // binds on any machine up to five times faster.
  std::string model = read_text(example("coupled_bushing_fit.rheo"));
  model = model.substr(0, model.find("fit {"));
  const fs::path file = scratch() / "time_limit.rheo", bounded = scratch() / "time_limit_block.rheo";
  write_text(file, model + fmt::format("fit {{\n  data \"{}\"\n}}\n", example("data/coupled_bushing_harmonic.csv")));
  write_text(bounded, model + fmt::format("fit {{\n  data \"{}\"\n  time_limit = 50 ms\n}}\n", example("data/coupled_bushing_harmonic.csv")));
  for (const auto& [command_binding, limit] :
       std::vector<std::pair<std::string, std::string>>{{fmt::format("fit {} --time-limit 0.05s --json", file.string()), "0.05 s"},
                                                        {fmt::format("fit {} --time-limit '0.0005 min' --json", file.string()), "0.03 s"},
                                                        {fmt::format("fit {} --json", bounded.string()), "0.05 s"}}) {
    const std::string command = command_binding;  // Clang 14 cannot capture a structured binding
    CAPTURE(command);
    const Run r = run(command);
    REQUIRE(r.code == 0);
    const json report = json::parse(r.out);
    CHECK(report["time_limited"] == true);
    CHECK(report["interrupted"] == false);
    CHECK(report["status"] == "TIME_LIMIT_REACHED");
    CHECK(report["evaluations"].get<int>() < 1000);
    CHECK(report["err"].get<double>() > 0.0);
    CHECK(contains(report["notes"].dump(), "stopped at the time limit of " + limit + " after"));
  }
  const Run unbounded = run(fmt::format("fit {} --max-evaluations 30 --json", file.string()));
  REQUIRE(unbounded.code == 0);
  CHECK(json::parse(unbounded.out)["time_limited"] == false);
}

TEST_CASE("--block N runs only the N-th fit block, so -o can name its output") {
  const fs::path out = scratch() / "block2.rheo";
  const Run r = run(fmt::format("fit {} --block 2 --json -o {}", example("specimen_d_methods.rheo"), out.string()));
  REQUIRE(r.code == 0);
  const json result = json::parse(r.out);
  CHECK(result["method"] == "approximate");
  CHECK(fs::exists(out));
}

}  // namespace cli_fit_test
