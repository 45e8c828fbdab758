// The FMU binary through the standard's C entry points, loaded as a host loads it (dlopen): what
// it exports and links, the call sequence, errors returned as fmi2Error with a logged message
// (never a crash), and FMU states through their serialized bytes.
#include "cli_support.hpp"
#include "fmi2_host.hpp"
#include "runtime/fmu/fmu_resources.hpp"
#include "runtime/fmu/fmu_variables.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>

namespace fmi2_entry_points_test {

using namespace rheo;

namespace {

// A resources folder for MODEL of SOURCE; returns its file: URI and sets GUID.
std::string resources(const std::filesystem::path& dir, const std::string& source, const std::string& model, std::string& guid) {
  std::filesystem::create_directories(dir);
  std::ofstream(dir / runtime::fmu::kSourceResource) << source;
  std::ofstream(dir / runtime::fmu::kModelNameResource) << model << "\n";
  guid = runtime::fmu::fmu_guid(RHEO_PROJECT_VERSION, model, source);
  return "file://" + dir.string() + "/";
}

bool logged(const std::string& part) {
  for (const auto& line : test::fmi2_log())
    if (line.find(part) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("fmi2 binary: it needs only the C library, libm and libgcc_s, and exports the FMI functions only") {
  if (!test::tool_installed("ldd", "libc-bin")) return;
  const test::BinaryRun ldd = [] {
    test::BinaryRun r;
    FILE* pipe = popen(("ldd " + std::string(RHEO_FMU_BINARY_PATH)).c_str(), "r");
    REQUIRE(pipe != nullptr);
    char buffer[512];
    while (std::fgets(buffer, sizeof buffer, pipe)) r.out += buffer;
    r.code = pclose(pipe);
    return r;
  }();
  REQUIRE(ldd.code == 0);
  const std::regex system_library(R"(^\s*(linux-vdso\.so\.1|libc\.so\.6|libm\.so\.6|libgcc_s\.so\.1|/lib64/ld-linux-x86-64\.so\.2)[\s=])");
  std::istringstream lines(ldd.out);
  int count = 0;
  for (std::string line; std::getline(lines, line); ++count) CHECK_MESSAGE(std::regex_search(line, system_library), line);
  CHECK(count >= 3);
  test::Fmi2Library fmu(RHEO_FMU_BINARY_PATH);
  CHECK(std::string(fmu.fmi2GetVersion()) == "2.0");
  CHECK(std::string(fmu.fmi2GetTypesPlatform()) == "default");
  CHECK(dlsym(fmu.handle, "_ZN4rheo7runtime3fmu12CoSimulation7do_stepEdd") == nullptr);  // rheo's own symbols stay inside
}

TEST_CASE("fmi2 binary: a step input through the C interface relaxes a Maxwell arm as k U exp(-t/tau)") {
  test::Fmi2Library fmu(RHEO_FMU_BINARY_PATH);
  std::string guid;
  const auto dir = test::scratch_directory("fmi2-binary") / "resources";
  const std::string uri = resources(dir, "model m { maxwell m1 (k = 50 N/mm, tau = 2 ms) }", "m", guid);
  fmi2Component c = fmu.fmi2Instantiate("m1", fmi2CoSimulation, guid.c_str(), uri.c_str(), test::fmi2_callbacks(), fmi2False, fmi2False);
  REQUIRE(c != nullptr);
  CHECK(fmu.fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0) == fmi2OK);
  CHECK(fmu.fmi2EnterInitializationMode(c) == fmi2OK);
  CHECK(fmu.fmi2ExitInitializationMode(c) == fmi2OK);
  const fmi2ValueReference u = runtime::fmu::kInputU, f = runtime::fmu::kOutputF;
  const double U = 0.25;
  CHECK(fmu.fmi2SetReal(c, &u, 1, &U) == fmi2OK);
  for (int n = 1; n <= 20; ++n) {
    REQUIRE(fmu.fmi2DoStep(c, (n - 1) * 1e-3, 1e-3, fmi2True) == fmi2OK);
    double force = 0.0;
    CHECK(fmu.fmi2GetReal(c, &f, 1, &force) == fmi2OK);
    CHECK(test::relative_error(force, 50.0 * U * std::exp(-n * 1e-3 / 2e-3)) < 1e-12);
  }
  double time = 0.0;
  CHECK(fmu.fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &time) == fmi2OK);
  CHECK(time == doctest::Approx(0.02).scale(0.0));
  CHECK(fmu.fmi2Terminate(c) == fmi2OK);
  fmu.fmi2FreeInstance(c);
  std::filesystem::remove_all(dir.parent_path());
}

TEST_CASE("fmi2 binary: bad input, bad steps and bad calls return fmi2Error with a logged message, and the FMU goes on") {
  test::Fmi2Library fmu(RHEO_FMU_BINARY_PATH);
  std::string guid;
  const auto dir = test::scratch_directory("fmi2-errors") / "resources";
  const std::string uri = resources(dir, "model m { spring s (k = 10 N/mm) }", "m", guid);
  test::fmi2_log().clear();
  CHECK(fmu.fmi2Instantiate("bad", fmi2CoSimulation, "{wrong}", uri.c_str(), test::fmi2_callbacks(), fmi2False, fmi2False) == nullptr);
  CHECK(logged("fmi2Instantiate: the host passed GUID {wrong}"));
  CHECK(fmu.fmi2Instantiate("me", fmi2ModelExchange, guid.c_str(), uri.c_str(), test::fmi2_callbacks(), fmi2False, fmi2False) == nullptr);
  CHECK(logged("co-simulation only"));
  fmi2Component c = fmu.fmi2Instantiate("ok", fmi2CoSimulation, guid.c_str(), uri.c_str(), test::fmi2_callbacks(), fmi2False, fmi2True);
  REQUIRE(c != nullptr);
  const fmi2String unknown[] = {"logEverything"};
  CHECK(fmu.fmi2SetDebugLogging(c, fmi2True, 1, unknown) == fmi2Error);
  const fmi2String known[] = {"logStatusError"};
  CHECK(fmu.fmi2SetDebugLogging(c, fmi2True, 1, known) == fmi2OK);
  CHECK(fmu.fmi2DoStep(c, 0.0, 1e-3, fmi2True) == fmi2Error);  // before initialisation
  CHECK(fmu.fmi2EnterInitializationMode(c) == fmi2OK);
  CHECK(fmu.fmi2ExitInitializationMode(c) == fmi2OK);
  const fmi2ValueReference u = runtime::fmu::kInputU, f = runtime::fmu::kOutputF, k = runtime::fmu::kFirstParameter;
  test::fmi2_log().clear();
  const double nan = std::numeric_limits<double>::quiet_NaN(), huge = 1e300, one = 1.0, two = 2.0;
  CHECK(fmu.fmi2SetReal(c, &u, 1, &nan) == fmi2Error);
  CHECK(logged("3 logStatusError: fmi2SetReal: u = nan: it must be a finite number"));
  CHECK(fmu.fmi2SetReal(c, &u, 1, &huge) == fmi2Error);
  CHECK(logged("lies outside its range"));
  CHECK(fmu.fmi2SetReal(c, &k, 1, &two) == fmi2Error);
  CHECK(logged("fixed once initialisation ends"));
  CHECK(fmu.fmi2SetReal(c, nullptr, 1, &one) == fmi2Error);
  CHECK(fmu.fmi2DoStep(c, 0.0, 0.0, fmi2True) == fmi2Error);
  CHECK(logged("fmi2DoStep: communication step size 0 s"));
  CHECK(fmu.fmi2DoStep(c, 0.0, -nan, fmi2True) == fmi2Error);
  CHECK(fmu.fmi2DoStep(c, 3.0, 1e-3, fmi2True) == fmi2Error);
  fmi2Integer i = 0;
  CHECK(fmu.fmi2GetInteger(c, &u, 1, &i) == fmi2Error);
  CHECK(fmu.fmi2DeSerializeFMUstate(c, "garbage", 7, nullptr) == fmi2Error);
  fmi2FMUstate bad = nullptr;
  CHECK(fmu.fmi2DeSerializeFMUstate(c, "garbage", 7, &bad) == fmi2Error);
  CHECK(bad == nullptr);
  CHECK(fmu.fmi2DoStep(nullptr, 0.0, 1e-3, fmi2True) == fmi2Error);
  // Nothing above changed the instance: it steps on from t = 0.
  CHECK(fmu.fmi2SetReal(c, &u, 1, &one) == fmi2OK);
  CHECK(fmu.fmi2DoStep(c, 0.0, 1e-3, fmi2True) == fmi2OK);
  double force = 0.0;
  CHECK(fmu.fmi2GetReal(c, &f, 1, &force) == fmi2OK);
  CHECK(force == 10.0);
  fmu.fmi2FreeInstance(c);
  std::filesystem::remove_all(dir.parent_path());
}

TEST_CASE("fmi2 binary: an FMU state serialized to bytes and read back repeats the steps after it") {
  test::Fmi2Library fmu(RHEO_FMU_BINARY_PATH);
  std::string guid;
  const auto dir = test::scratch_directory("fmi2-state") / "resources";
  const std::string uri = resources(dir, test::read_file(std::string(RHEO_EXAMPLES_DIR) + "/hydrobushing.rheo"), "hydrobushing", guid);
  fmi2Component c = fmu.fmi2Instantiate("h", fmi2CoSimulation, guid.c_str(), uri.c_str(), test::fmi2_callbacks(), fmi2False, fmi2False);
  REQUIRE(c != nullptr);
  REQUIRE(fmu.fmi2EnterInitializationMode(c) == fmi2OK);
  REQUIRE(fmu.fmi2ExitInitializationMode(c) == fmi2OK);
  const fmi2ValueReference u = runtime::fmu::kInputU, f = runtime::fmu::kOutputF;
  auto run = [&](int from, int to) {
    std::vector<double> forces;
    for (int n = from; n < to; ++n) {
      const double value = 0.6 * std::sin(0.05 * n), rate = 0.6 * 0.05 * std::cos(0.05 * n) / 1e-3;
      const fmi2Integer order = 1;
      REQUIRE(fmu.fmi2SetReal(c, &u, 1, &value) == fmi2OK);
      REQUIRE(fmu.fmi2SetRealInputDerivatives(c, &u, 1, &order, &rate) == fmi2OK);
      REQUIRE(fmu.fmi2DoStep(c, n * 1e-3, 1e-3, fmi2False) == fmi2OK);
      double force = 0.0;
      REQUIRE(fmu.fmi2GetReal(c, &f, 1, &force) == fmi2OK);
      forces.push_back(force);
    }
    return forces;
  };
  run(0, 60);
  fmi2FMUstate state = nullptr;
  REQUIRE(fmu.fmi2GetFMUstate(c, &state) == fmi2OK);
  size_t size = 0;
  REQUIRE(fmu.fmi2SerializedFMUstateSize(c, state, &size) == fmi2OK);
  std::vector<char> bytes(size);
  REQUIRE(fmu.fmi2SerializeFMUstate(c, state, bytes.data(), size) == fmi2OK);
  CHECK(fmu.fmi2SerializeFMUstate(c, state, bytes.data(), size - 1) == fmi2Error);
  CHECK(fmu.fmi2FreeFMUstate(c, &state) == fmi2OK);
  CHECK(state == nullptr);
  const auto first = run(60, 120);
  fmi2FMUstate read = nullptr;
  REQUIRE(fmu.fmi2DeSerializeFMUstate(c, bytes.data(), bytes.size(), &read) == fmi2OK);
  REQUIRE(fmu.fmi2SetFMUstate(c, read) == fmi2OK);
  CHECK(run(60, 120) == first);
  CHECK(fmu.fmi2FreeFMUstate(c, &read) == fmi2OK);
  CHECK(read == nullptr);
  // A freed or foreign state is an error, not a crash; a host that passes the state itself to
  // fmi2FreeFMUstate instead of its address (fmusim 31d7d40) gets it freed.
  double not_a_state = 0.0;
  CHECK(fmu.fmi2SetFMUstate(c, &not_a_state) == fmi2Error);
  REQUIRE(fmu.fmi2GetFMUstate(c, &state) == fmi2OK);
  CHECK(fmu.fmi2FreeFMUstate(c, static_cast<fmi2FMUstate*>(state)) == fmi2OK);
  CHECK(fmu.fmi2SetFMUstate(c, state) == fmi2Error);
  state = nullptr;
  REQUIRE(fmu.fmi2GetFMUstate(c, &state) == fmi2OK);  // left for fmi2FreeInstance to free
  CHECK(fmu.fmi2Reset(c) == fmi2OK);
  fmu.fmi2FreeInstance(c);
  std::filesystem::remove_all(dir.parent_path());
}

}  // namespace fmi2_entry_points_test
