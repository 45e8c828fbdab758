// An exported FMU's step against rheo's own (#27 "Speed"): ns per fmi2DoStep of specimen D and
// the hydrobushing, through the FMI entry points of the FMU binary this build made (dlopen, as a
// host loads it; each step a host's fmi2SetReal, fmi2DoStep and fmi2GetReal), against ns per
// step of run_history, what `rheo simulate --solver fixed` runs, on the same samples.
// Drive: 2 mm at 1.5 Hz plus 0.1 mm at 23 Hz, h = 0.1 ms, 1e5 steps per run.
//   _Held:  the input held over each step (FMI's default): a jump at every step, exact in one
//           kernel pass where every element is in the model's body (specimen D); into a subtree
//           (the hydrobushing's capped fluid branch) a ramp of h/2^10 and the rest of the step,
//           taken in one pass of composed maps (stepping/jump_hold.hpp);
//   _Ramp:  the host passes du/dt = (u_{n+1} - u_n)/h (fmi2SetRealInputDerivatives): the path is
//           rheo's piecewise-linear drive, one kernel pass per step. The host's derivatives are
//           computed before the timed loop, as its inputs are: the host's arithmetic (a division
//           a step, on the step's path) is not the FMU's.
#include "bench_support.hpp"
#include "fmi2Functions.h"
#include "runtime/fmu/fmu_resources.hpp"
#include "runtime/fmu/fmu_variables.hpp"
#include "runtime/protocols/run_history.hpp"

#include <benchmark/benchmark.h>
#include <dlfcn.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace rheo;

constexpr double kStep = 1e-4;  // s
constexpr int kSteps = 100'000;

std::vector<double> displacements() {
  std::vector<double> u(kSteps + 1);
  for (int k = 0; k <= kSteps; ++k) {
    const double t = k * kStep;
    u[static_cast<std::size_t>(k)] = 2.0 * std::sin(2 * std::numbers::pi * 1.5 * t) + 0.1 * std::sin(2 * std::numbers::pi * 23.0 * t);
  }
  return u;
}

std::string example_text(const std::string& file) {
  std::ifstream in(std::string(RHEO_EXAMPLES_DIR) + "/" + file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void no_log(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, ...) {}

// One instance of the FMU binary for MODEL of examples/FILE, initialised at u = 0.
struct FmuInstance {
  void* library = nullptr;
  fmi2Component c = nullptr;
  fmi2SetRealTYPE* set_real = nullptr;
  fmi2GetRealTYPE* get_real = nullptr;
  fmi2DoStepTYPE* do_step = nullptr;
  fmi2SetRealInputDerivativesTYPE* set_derivative = nullptr;
  fmi2FreeInstanceTYPE* free_instance = nullptr;
  std::filesystem::path folder;

  template <class F>
  F* symbol(const char* name) {
    void* f = dlsym(library, name);
    if (!f) throw std::runtime_error(std::string(name) + " is not exported");
    return reinterpret_cast<F*>(f);
  }

  FmuInstance(const std::string& file, const std::string& model) {
    library = dlopen(RHEO_FMU_BINARY_PATH, RTLD_NOW | RTLD_LOCAL);
    if (!library) throw std::runtime_error(dlerror());
    folder = std::filesystem::temp_directory_path() / ("rheo-fmu-bench-" + std::to_string(::getpid()) + "-" + model);
    std::filesystem::create_directories(folder);
    const std::string source = example_text(file);
    std::ofstream(folder / runtime::fmu::kSourceResource) << source;
    std::ofstream(folder / runtime::fmu::kModelNameResource) << model << "\n";
    const std::string guid = runtime::fmu::fmu_guid(RHEO_PROJECT_VERSION, model, source), uri = "file://" + folder.string() + "/";
    static const fmi2CallbackFunctions callbacks{no_log, std::calloc, std::free, nullptr, nullptr};
    c = symbol<fmi2InstantiateTYPE>("fmi2Instantiate")("bench", fmi2CoSimulation, guid.c_str(), uri.c_str(), &callbacks, fmi2False, fmi2False);
    if (!c) throw std::runtime_error("fmi2Instantiate failed");
    if (symbol<fmi2EnterInitializationModeTYPE>("fmi2EnterInitializationMode")(c) != fmi2OK ||
        symbol<fmi2ExitInitializationModeTYPE>("fmi2ExitInitializationMode")(c) != fmi2OK)
      throw std::runtime_error("initialisation failed");
    set_real = symbol<fmi2SetRealTYPE>("fmi2SetReal");
    get_real = symbol<fmi2GetRealTYPE>("fmi2GetReal");
    do_step = symbol<fmi2DoStepTYPE>("fmi2DoStep");
    set_derivative = symbol<fmi2SetRealInputDerivativesTYPE>("fmi2SetRealInputDerivatives");
    free_instance = symbol<fmi2FreeInstanceTYPE>("fmi2FreeInstance");
  }
  ~FmuInstance() {
    if (c) free_instance(c);
    if (library) dlclose(library);
    std::filesystem::remove_all(folder);
  }
};

void fmu_steps(benchmark::State& state, const std::string& file, const std::string& model, bool ramp) {
  FmuInstance fmu(file, model);
  const std::vector<double> u = displacements();
  // The host's input derivatives, as its integrator has them: computed outside the timed loop,
  // like the inputs themselves.
  std::vector<double> rates(kSteps);
  for (std::size_t i = 0; i < rates.size(); ++i) rates[i] = (u[i + 1] - u[i]) / kStep;
  const fmi2ValueReference in = runtime::fmu::kInputU, out = runtime::fmu::kOutputF;
  const fmi2Integer order = 1;
  double t = 0.0, force = 0.0;
  for (auto _ : state) {
    for (int k = 0; k < kSteps; ++k) {
      const auto i = static_cast<std::size_t>(k);
      fmu.set_real(fmu.c, &in, 1, &u[i]);
      if (ramp) fmu.set_derivative(fmu.c, &in, 1, &order, &rates[i]);
      if (fmu.do_step(fmu.c, t, kStep, fmi2True) != fmi2OK) {
        state.SkipWithError("fmi2DoStep failed");
        return;
      }
      fmu.get_real(fmu.c, &out, 1, &force);
      t += kStep;
    }
    benchmark::DoNotOptimize(force);
  }
  state.counters["ns_per_step"] = benchmark::Counter(static_cast<double>(state.iterations()) * kSteps,
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert, benchmark::Counter::kIs1000);
}

void rheo_steps(benchmark::State& state, const std::string& file, const std::string& model) {
  const runtime::Network network = runtime::Network::compile(bench::example_model(file, model));
  runtime::Drive drive;
  drive.displacement = displacements();
  for (int k = 0; k <= kSteps; ++k) drive.time.push_back(k * kStep);
  for (auto _ : state) {
    const runtime::History h = runtime::run_history(network, drive, false, runtime::SolverChoice::fixed);
    benchmark::DoNotOptimize(h.force.data());
  }
  state.counters["ns_per_step"] = benchmark::Counter(static_cast<double>(state.iterations()) * kSteps,
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert, benchmark::Counter::kIs1000);
}

void BM_Fmu_SpecimenD_Held(benchmark::State& s) { fmu_steps(s, "specimen_d.rheo", "specimen_d", false); }
void BM_Fmu_SpecimenD_Ramp(benchmark::State& s) { fmu_steps(s, "specimen_d.rheo", "specimen_d", true); }
void BM_Rheo_SpecimenD_Steps(benchmark::State& s) { rheo_steps(s, "specimen_d.rheo", "specimen_d"); }
void BM_Fmu_Hydrobushing_Held(benchmark::State& s) { fmu_steps(s, "hydrobushing.rheo", "hydrobushing", false); }
void BM_Fmu_Hydrobushing_Ramp(benchmark::State& s) { fmu_steps(s, "hydrobushing.rheo", "hydrobushing", true); }
void BM_Rheo_Hydrobushing_Steps(benchmark::State& s) { rheo_steps(s, "hydrobushing.rheo", "hydrobushing"); }

}  // namespace

BENCHMARK(BM_Rheo_SpecimenD_Steps)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Fmu_SpecimenD_Held)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Fmu_SpecimenD_Ramp)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Rheo_Hydrobushing_Steps)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Fmu_Hydrobushing_Held)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Fmu_Hydrobushing_Ramp)->Unit(benchmark::kMillisecond);
