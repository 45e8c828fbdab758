// The FMU binary through the FMI 3.0 C entry points, loaded as a host loads it (dlopen): every
// function the standard's header declares is exported, the call sequence of co-simulation with
// fmi3DoStep's out-arguments, errors returned as fmi3Error with a logged message (never a crash),
// and FMU states through their serialized bytes.
#include "cli_support.hpp"
#include "fmi3_host.hpp"
#include "runtime/fmu/fmu_resources.hpp"
#include "runtime/fmu/fmu_variables.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>

namespace fmi3_entry_points_test {

using namespace rheo;

namespace {

// A resources folder for MODEL of SOURCE; returns its path (FMI 3.0's resourcePath: a native path
// with a trailing separator) and sets TOKEN.
std::string resources(const std::filesystem::path& dir, const std::string& source, const std::string& model, std::string& token) {
  std::filesystem::create_directories(dir);
  std::ofstream(dir / runtime::fmu::kSourceResource) << source;
  std::ofstream(dir / runtime::fmu::kModelNameResource) << model << "\n";
  token = runtime::fmu::fmu_guid(RHEO_PROJECT_VERSION, model, source);
  return dir.string() + "/";
}

bool logged(const std::string& part) {
  for (const auto& line : test::fmi3_log())
    if (line.find(part) != std::string::npos) return true;
  return false;
}

fmi3Instance instantiate(test::Fmi3Library& fmu, const std::string& token, const std::string& path, fmi3Boolean event_mode = fmi3False) {
  return fmu.fmi3InstantiateCoSimulation("i", token.c_str(), path.c_str(), fmi3False, fmi3False, event_mode, fmi3False, nullptr, 0, nullptr,
                                         test::fmi3_logger, nullptr);
}

// An instance of a 10 N/mm spring, instantiated with loggingOn false; its resources under the
// scratch directory NAME, removed with it.
struct SpringFmu {
  test::Fmi3Library fmu{RHEO_FMU_BINARY_PATH};
  std::filesystem::path dir;
  std::string token, path;
  fmi3Instance c = nullptr;
  fmi3Boolean event = fmi3False, terminate = fmi3False, early = fmi3False;
  double last = 0.0;
  explicit SpringFmu(const char* name) : dir(test::scratch_directory(name) / "resources") {
    path = resources(dir, "model m { spring s (k = 10 N/mm) }", "m", token);
    c = instantiate(fmu, token, path);
    REQUIRE(c != nullptr);
  }
  ~SpringFmu() {
    fmu.fmi3FreeInstance(c);
    std::filesystem::remove_all(dir.parent_path());
  }
  SpringFmu(const SpringFmu&) = delete;
  SpringFmu& operator=(const SpringFmu&) = delete;
  fmi3Status step(double t) { return fmu.fmi3DoStep(c, t, 1e-3, fmi3True, &event, &terminate, &early, &last); }
  fmi3Status set_u(double value) {
    const fmi3ValueReference u = runtime::fmu::kInputU;
    return fmu.fmi3SetFloat64(c, &u, 1, &value, 1);
  }
  fmi3Status get_force(double& force) {
    const fmi3ValueReference f = runtime::fmu::kOutputF;
    return fmu.fmi3GetFloat64(c, &f, 1, &force, 1);
  }
  fmi3Status start() {
    const fmi3Status entered = fmu.fmi3EnterInitializationMode(c, fmi3False, 0.0, 0.0, fmi3False, 0.0);
    return entered == fmi3OK ? fmu.fmi3ExitInitializationMode(c) : entered;
  }
};

}  // namespace

TEST_CASE("fmi3 binary: it exports every function fmi3Functions.h declares, and reports version 3.0") {
  const std::string header = test::read_file(std::string(RHEO_SOURCE_DIR) + "/third_party/fmi3/fmi3Functions.h");
  const std::regex declared(R"(FMI3_Export (fmi3[A-Za-z0-9]+)TYPE)");
  test::Fmi3Library fmu(RHEO_FMU_BINARY_PATH);
  int count = 0;
  for (std::sregex_iterator m(header.begin(), header.end(), declared), end; m != end; ++m, ++count)
    CHECK_MESSAGE(dlsym(fmu.handle, (*m)[1].str().c_str()) != nullptr, (*m)[1].str());
  CHECK(count == 75);  // FMI 3.0's functions, model exchange and scheduled execution included
  CHECK(std::string(fmu.fmi3GetVersion()) == "3.0");
}

TEST_CASE("fmi3 binary: a step input through the C interface relaxes a Maxwell arm as k U exp(-t/tau)") {
  test::Fmi3Library fmu(RHEO_FMU_BINARY_PATH);
  std::string token;
  const auto dir = test::scratch_directory("fmi3-binary") / "resources";
  const std::string path = resources(dir, "model m { maxwell m1 (k = 50 N/mm, tau = 2 ms) }", "m", token);
  fmi3Instance c = instantiate(fmu, token, path);
  REQUIRE(c != nullptr);
  CHECK(fmu.fmi3EnterInitializationMode(c, fmi3False, 0.0, 1.0, fmi3False, 0.0) == fmi3OK);
  CHECK(fmu.fmi3ExitInitializationMode(c) == fmi3OK);
  const fmi3ValueReference u = runtime::fmu::kInputU, f = runtime::fmu::kOutputF, time = 6;  // after u, F, v and k, tau, c
  const double U = 0.25;
  CHECK(fmu.fmi3SetFloat64(c, &u, 1, &U, 1) == fmi3OK);
  for (int n = 1; n <= 20; ++n) {
    fmi3Boolean event = fmi3True, terminate = fmi3True, early = fmi3True;
    double last = 0.0;
    REQUIRE(fmu.fmi3DoStep(c, 1.0 + (n - 1) * 1e-3, 1e-3, fmi3True, &event, &terminate, &early, &last) == fmi3OK);
    CHECK_FALSE(event);
    CHECK_FALSE(terminate);
    CHECK_FALSE(early);
    CHECK(last == doctest::Approx(1.0 + n * 1e-3).epsilon(1e-15));
    const fmi3ValueReference both[] = {f, time};
    double values[2] = {};
    CHECK(fmu.fmi3GetFloat64(c, both, 2, values, 2) == fmi3OK);
    CHECK(test::relative_error(values[0], 50.0 * U * std::exp(-n * 1e-3 / 2e-3)) < 1e-12);
    CHECK(values[1] == last);
  }
  CHECK(fmu.fmi3Terminate(c) == fmi3OK);
  fmu.fmi3FreeInstance(c);
  std::filesystem::remove_all(dir.parent_path());
}

TEST_CASE("fmi3 binary: bad input, bad calls and unsupported functions return fmi3Error with a logged message, and the FMU goes on") {
  test::Fmi3Library fmu(RHEO_FMU_BINARY_PATH);
  std::string token;
  const auto dir = test::scratch_directory("fmi3-errors") / "resources";
  const std::string path = resources(dir, "model m { spring s (k = 10 N/mm) }", "m", token);
  test::fmi3_log().clear();
  CHECK(instantiate(fmu, "{wrong}", path) == nullptr);
  CHECK(logged("3 logStatusError: fmi3InstantiateCoSimulation: the host passed instantiationToken {wrong}"));
  CHECK(instantiate(fmu, token, path, fmi3True) == nullptr);
  CHECK(logged("no event mode (hasEventMode false)"));
  CHECK(fmu.fmi3InstantiateModelExchange("me", token.c_str(), path.c_str(), fmi3False, fmi3False, nullptr, test::fmi3_logger) == nullptr);
  CHECK(logged("fmi3InstantiateModelExchange: this FMU is for co-simulation only"));
  fmi3Instance c = instantiate(fmu, token, path);
  REQUIRE(c != nullptr);
  const fmi3String unknown[] = {"logEverything"};
  CHECK(fmu.fmi3SetDebugLogging(c, fmi3True, 1, unknown) == fmi3Error);
  const fmi3String known[] = {"logStatusError"};
  CHECK(fmu.fmi3SetDebugLogging(c, fmi3True, 1, known) == fmi3OK);
  fmi3Boolean event = fmi3False, terminate = fmi3False, early = fmi3False;
  double last = 0.0;
  CHECK(fmu.fmi3DoStep(c, 0.0, 1e-3, fmi3True, &event, &terminate, &early, &last) == fmi3Error);  // before initialisation
  CHECK(fmu.fmi3EnterInitializationMode(c, fmi3False, 0.0, 0.0, fmi3False, 0.0) == fmi3OK);
  CHECK(fmu.fmi3ExitInitializationMode(c) == fmi3OK);
  const fmi3ValueReference u = runtime::fmu::kInputU, f = runtime::fmu::kOutputF, k = runtime::fmu::kFirstParameter;
  test::fmi3_log().clear();
  const double nan = std::numeric_limits<double>::quiet_NaN(), huge = 1e300, one = 1.0, two = 2.0;
  CHECK(fmu.fmi3SetFloat64(c, &u, 1, &nan, 1) == fmi3Error);
  CHECK(logged("3 logStatusError: fmi3SetFloat64: u = nan: it must be a finite number"));
  CHECK(fmu.fmi3SetFloat64(c, &u, 1, &huge, 1) == fmi3Error);
  CHECK(logged("lies outside its range"));
  CHECK(fmu.fmi3SetFloat64(c, &k, 1, &two, 1) == fmi3Error);
  CHECK(logged("set it before fmi3ExitInitializationMode"));
  CHECK(fmu.fmi3SetFloat64(c, &u, 1, &one, 2) == fmi3Error);
  CHECK(logged("nValues is 2 for 1 value references"));
  CHECK(fmu.fmi3SetFloat64(c, nullptr, 1, &one, 1) == fmi3Error);
  CHECK(fmu.fmi3DoStep(c, 0.0, 0.0, fmi3True, &event, &terminate, &early, &last) == fmi3Error);
  CHECK(logged("fmi3DoStep: communication step size 0 s"));
  CHECK(fmu.fmi3DoStep(c, 3.0, 1e-3, fmi3True, &event, &terminate, &early, &last) == fmi3Error);
  CHECK(fmu.fmi3DoStep(c, 0.0, 1e-3, fmi3True, nullptr, &terminate, &early, &last) == fmi3Error);
  fmi3Int32 i = 0;
  CHECK(fmu.fmi3GetInt32(c, &u, 1, &i, 1) == fmi3Error);
  CHECK(fmu.fmi3GetInt32(c, nullptr, 0, nullptr, 0) == fmi3OK);
  test::fmi3_log().clear();
  CHECK(fmu.fmi3EnterEventMode(c) == fmi3Error);
  CHECK(fmu.fmi3EnterStepMode(c) == fmi3Error);
  CHECK(fmu.fmi3SetTime(c, 1.0) == fmi3Error);
  CHECK(fmu.fmi3GetDirectionalDerivative(c, &f, 1, &u, 1, &one, 1, &last, 1) == fmi3Error);
  CHECK(fmu.fmi3UpdateDiscreteStates(c, &event, &terminate, &early, &early, &early, &last) == fmi3Error);
  CHECK(test::fmi3_log().size() == 5);
  CHECK(logged("fmi3SetTime: this FMU is for co-simulation only"));
  CHECK(logged("fmi3GetDirectionalDerivative: the FMU provides no partial derivatives"));
  fmi3FMUState bad = nullptr;
  const fmi3Byte garbage[] = {1, 2, 3};
  CHECK(fmu.fmi3DeserializeFMUState(c, garbage, 3, &bad) == fmi3Error);
  CHECK(bad == nullptr);
  CHECK(fmu.fmi3DoStep(nullptr, 0.0, 1e-3, fmi3True, &event, &terminate, &early, &last) == fmi3Error);
  // Nothing above changed the instance: it steps on from t = 0.
  CHECK(fmu.fmi3SetFloat64(c, &u, 1, &one, 1) == fmi3OK);
  CHECK(fmu.fmi3DoStep(c, 0.0, 1e-3, fmi3True, &event, &terminate, &early, &last) == fmi3OK);
  double force = 0.0;
  CHECK(fmu.fmi3GetFloat64(c, &f, 1, &force, 1) == fmi3OK);
  CHECK(force == 10.0);
  CHECK(fmu.fmi3Reset(c) == fmi3OK);
  fmu.fmi3FreeInstance(c);
  std::filesystem::remove_all(dir.parent_path());
}

TEST_CASE("fmi3 binary: an FMU state serialized to bytes and read back repeats the steps after it, ramped with v") {
  test::Fmi3Library fmu(RHEO_FMU_BINARY_PATH);
  std::string token;
  const auto dir = test::scratch_directory("fmi3-state") / "resources";
  const std::string path = resources(dir, test::read_file(std::string(RHEO_EXAMPLES_DIR) + "/hydrobushing.rheo"), "hydrobushing", token);
  fmi3Instance c = instantiate(fmu, token, path);
  REQUIRE(c != nullptr);
  REQUIRE(fmu.fmi3EnterInitializationMode(c, fmi3False, 0.0, 0.0, fmi3False, 0.0) == fmi3OK);
  REQUIRE(fmu.fmi3ExitInitializationMode(c) == fmi3OK);
  const fmi3ValueReference uv[] = {runtime::fmu::kInputU, runtime::fmu::kInputV}, f = runtime::fmu::kOutputF;
  auto run = [&](int from, int to) {
    std::vector<double> forces;
    for (int n = from; n < to; ++n) {
      // FMI 3.0 co-simulation passes no input derivatives: the velocity input v ramps u over the step.
      const double values[] = {0.6 * std::sin(0.05 * n), 0.6 * 0.05 * std::cos(0.05 * n) / 1e-3};
      fmi3Boolean event = fmi3False, terminate = fmi3False, early = fmi3False;
      double last = 0.0, force = 0.0;
      REQUIRE(fmu.fmi3SetFloat64(c, uv, 2, values, 2) == fmi3OK);
      REQUIRE(fmu.fmi3DoStep(c, n * 1e-3, 1e-3, fmi3False, &event, &terminate, &early, &last) == fmi3OK);
      REQUIRE(fmu.fmi3GetFloat64(c, &f, 1, &force, 1) == fmi3OK);
      forces.push_back(force);
    }
    return forces;
  };
  run(0, 60);
  fmi3FMUState state = nullptr;
  REQUIRE(fmu.fmi3GetFMUState(c, &state) == fmi3OK);
  size_t size = 0;
  REQUIRE(fmu.fmi3SerializedFMUStateSize(c, state, &size) == fmi3OK);
  std::vector<fmi3Byte> bytes(size);
  REQUIRE(fmu.fmi3SerializeFMUState(c, state, bytes.data(), size) == fmi3OK);
  CHECK(fmu.fmi3SerializeFMUState(c, state, bytes.data(), size - 1) == fmi3Error);
  CHECK(fmu.fmi3FreeFMUState(c, &state) == fmi3OK);
  CHECK(state == nullptr);
  const auto first = run(60, 120);
  fmi3FMUState read = nullptr;
  REQUIRE(fmu.fmi3DeserializeFMUState(c, bytes.data(), bytes.size(), &read) == fmi3OK);
  REQUIRE(fmu.fmi3SetFMUState(c, read) == fmi3OK);
  CHECK(run(60, 120) == first);
  CHECK(fmu.fmi3FreeFMUState(c, &read) == fmi3OK);
  double not_a_state = 0.0;
  CHECK(fmu.fmi3SetFMUState(c, &not_a_state) == fmi3Error);
  REQUIRE(fmu.fmi3GetFMUState(c, &state) == fmi3OK);  // left for fmi3FreeInstance to free
  fmu.fmi3FreeInstance(c);
  std::filesystem::remove_all(dir.parent_path());
}

// FMI 3.0.3 section 2.2.4 (clarifying 3.0): with logging off (loggingOn false at instantiation, or
// switched off by fmi3SetDebugLogging) the FMU must not call logMessage, except for fmi3Error and
// fmi3Fatal, which it should log whatever the settings; with a NULL logMessage it calls nothing.
TEST_CASE("fmi3 binary: with logging off nothing is logged but errors, which are logged whatever the settings") {
  SpringFmu s("fmi3-logging");
  double force = 0.0;
  test::fmi3_log().clear();
  CHECK(s.start() == fmi3OK);
  CHECK(s.set_u(1.0) == fmi3OK);
  CHECK(s.step(0.0) == fmi3OK);
  CHECK(s.get_force(force) == fmi3OK);
  CHECK(s.fmu.fmi3Terminate(s.c) == fmi3OK);
  CHECK(s.fmu.fmi3Reset(s.c) == fmi3OK);
  CHECK(test::fmi3_log().empty());
  CHECK(s.step(5.0) == fmi3Error);
  CHECK(test::fmi3_log().size() == 1);
  // Switched off for every category, and for the error category by name: errors still logged.
  const fmi3String errors[] = {"logStatusError"};
  for (size_t n : {size_t{0}, size_t{1}}) {
    CHECK(s.fmu.fmi3SetDebugLogging(s.c, fmi3False, n, n ? errors : nullptr) == fmi3OK);
    test::fmi3_log().clear();
    CHECK(s.step(5.0) == fmi3Error);
    REQUIRE(test::fmi3_log().size() == 1);
    CHECK(test::fmi3_log()[0].starts_with("3 logStatusError: fmi3DoStep: fmi3DoStep is called after initialisation"));
  }
  // No logger: the error is returned, nothing is called.
  fmi3Instance quiet = s.fmu.fmi3InstantiateCoSimulation("q", s.token.c_str(), s.path.c_str(), fmi3False, fmi3True, fmi3False, fmi3False, nullptr,
                                                         0, nullptr, nullptr, nullptr);
  REQUIRE(quiet != nullptr);
  CHECK(s.fmu.fmi3DoStep(quiet, 0.0, 1e-3, fmi3True, &s.event, &s.terminate, &s.early, &s.last) == fmi3Error);
  s.fmu.fmi3FreeInstance(quiet);
}

// FMI 3.0 section 2.3.4: fmi3Terminate belongs to super state Initialized (Event, Step,
// Continuous-Time, Clock Activation and Reconfiguration Mode). Without event mode, clocks,
// model exchange or structural parameters, this FMU's only state of it is Step Mode, entered by
// fmi3ExitInitializationMode; elsewhere (Instantiated, Initialization Mode, Terminated) the call
// is out of sequence: fmi3Error (section 2.2.4).
TEST_CASE("fmi3 binary: fmi3Terminate is taken in Step Mode, before or after steps, and refused out of sequence") {
  SpringFmu s("fmi3-terminate");
  test::fmi3_log().clear();
  CHECK(s.fmu.fmi3Terminate(s.c) == fmi3Error);  // Instantiated
  CHECK(logged("fmi3Terminate: fmi3Terminate is called after initialisation, not instantiated"));
  CHECK(s.fmu.fmi3EnterInitializationMode(s.c, fmi3False, 0.0, 0.0, fmi3False, 0.0) == fmi3OK);
  CHECK(s.fmu.fmi3Terminate(s.c) == fmi3Error);  // Initialization Mode
  CHECK(logged("not in initialisation mode"));
  CHECK(s.fmu.fmi3ExitInitializationMode(s.c) == fmi3OK);
  CHECK(s.fmu.fmi3Terminate(s.c) == fmi3OK);     // Step Mode, no step taken
  CHECK(s.fmu.fmi3Terminate(s.c) == fmi3Error);  // Terminated
  double force = -1.0;
  CHECK(s.step(0.0) == fmi3Error);
  CHECK(s.get_force(force) == fmi3OK);
  CHECK(force == 0.0);
  CHECK(s.fmu.fmi3Reset(s.c) == fmi3OK);
  CHECK(s.start() == fmi3OK);
  CHECK(s.set_u(0.5) == fmi3OK);
  CHECK(s.step(0.0) == fmi3OK);
  CHECK(s.fmu.fmi3Terminate(s.c) == fmi3OK);  // Step Mode after a step
  CHECK(s.get_force(force) == fmi3OK);
  CHECK(force == 5.0);  // the last step's result, readable in Terminated
}

}  // namespace fmi3_entry_points_test
