// The FMI 3.0 entry points' step (#27 "Speed"): ns per fmi3DoStep of specimen D and the
// hydrobushing through the FMU binary this build made (dlopen, as a host loads it; each step a
// host's fmi3SetFloat64, fmi3DoStep with its out-arguments and fmi3GetFloat64), on the drive of
// fmu_bench.cpp, to set beside its BM_Rheo_* (rheo's own step) and BM_Fmu_* (FMI 2.0) rows.
//   _Held:  the input held over each step (FMI's default), as BM_Fmu_*_Held;
//   _Ramp:  the host sets u and the velocity v = (u_{n+1} - u_n)/h in one fmi3SetFloat64 (FMI 3.0
//           co-simulation has no input derivatives): rheo's piecewise-linear drive, one kernel
//           pass per step.
#include "fmi3Functions.h"
#include "runtime/fmu/fmu_resources.hpp"
#include "runtime/fmu/fmu_variables.hpp"

#include <benchmark/benchmark.h>
#include <dlfcn.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace rheo;

constexpr double kStep = 1e-4;  // s, as fmu_bench.cpp
constexpr int kSteps = 100'000;

std::vector<double> displacements() {
  std::vector<double> u(kSteps + 1);
  for (int k = 0; k <= kSteps; ++k) {
    const double t = k * kStep;
    u[static_cast<std::size_t>(k)] = 2.0 * std::sin(2 * std::numbers::pi * 1.5 * t) + 0.1 * std::sin(2 * std::numbers::pi * 23.0 * t);
  }
  return u;
}

// One FMI 3.0 instance of the FMU binary for MODEL of examples/FILE, initialised at u = 0.
struct Fmi3Instance {
  void* library = nullptr;
  fmi3Instance c = nullptr;
  fmi3SetFloat64TYPE* set_float64 = nullptr;
  fmi3GetFloat64TYPE* get_float64 = nullptr;
  fmi3DoStepTYPE* do_step = nullptr;
  fmi3FreeInstanceTYPE* free_instance = nullptr;
  std::filesystem::path folder;

  template <class F>
  F* symbol(const char* name) {
    void* f = dlsym(library, name);
    if (!f) throw std::runtime_error(std::string(name) + " is not exported");
    return reinterpret_cast<F*>(f);
  }

  Fmi3Instance(const std::string& file, const std::string& model) {
    library = dlopen(RHEO_FMU_BINARY_PATH, RTLD_NOW | RTLD_LOCAL);
    if (!library) throw std::runtime_error(dlerror());
    folder = std::filesystem::temp_directory_path() / ("rheo-fmi3-bench-" + std::to_string(::getpid()) + "-" + model);
    std::filesystem::create_directories(folder);
    std::ifstream in(std::string(RHEO_EXAMPLES_DIR) + "/" + file);
    std::stringstream text;
    text << in.rdbuf();
    const std::string source = text.str();
    std::ofstream(folder / runtime::fmu::kSourceResource) << source;
    std::ofstream(folder / runtime::fmu::kModelNameResource) << model << "\n";
    const std::string token = runtime::fmu::fmu_guid(RHEO_PROJECT_VERSION, model, source), path = folder.string() + "/";
    c = symbol<fmi3InstantiateCoSimulationTYPE>("fmi3InstantiateCoSimulation")("bench", token.c_str(), path.c_str(), fmi3False, fmi3False,
                                                                               fmi3False, fmi3False, nullptr, 0, nullptr, nullptr, nullptr);
    if (!c) throw std::runtime_error("fmi3InstantiateCoSimulation failed");
    if (symbol<fmi3EnterInitializationModeTYPE>("fmi3EnterInitializationMode")(c, fmi3False, 0.0, 0.0, fmi3False, 0.0) != fmi3OK ||
        symbol<fmi3ExitInitializationModeTYPE>("fmi3ExitInitializationMode")(c) != fmi3OK)
      throw std::runtime_error("initialisation failed");
    set_float64 = symbol<fmi3SetFloat64TYPE>("fmi3SetFloat64");
    get_float64 = symbol<fmi3GetFloat64TYPE>("fmi3GetFloat64");
    do_step = symbol<fmi3DoStepTYPE>("fmi3DoStep");
    free_instance = symbol<fmi3FreeInstanceTYPE>("fmi3FreeInstance");
  }
  ~Fmi3Instance() {
    if (c) free_instance(c);
    if (library) dlclose(library);
    std::filesystem::remove_all(folder);
  }
};

void fmi3_steps(benchmark::State& state, const std::string& file, const std::string& model, bool ramp) {
  Fmi3Instance fmu(file, model);
  const std::vector<double> u = displacements();
  std::vector<double> v(kSteps);  // the host's velocities, outside the timed loop (fmu_bench.cpp)
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = (u[i + 1] - u[i]) / kStep;
  const fmi3ValueReference inputs[] = {runtime::fmu::kInputU, runtime::fmu::kInputV}, out = runtime::fmu::kOutputF;
  const std::size_t n_inputs = ramp ? 2 : 1;
  double t = 0.0, force = 0.0, last = 0.0;
  fmi3Boolean event = fmi3False, terminate = fmi3False, early = fmi3False;
  for (auto _ : state) {
    for (int k = 0; k < kSteps; ++k) {
      const auto i = static_cast<std::size_t>(k);
      const double values[] = {u[i], v[i]};
      fmu.set_float64(fmu.c, inputs, n_inputs, values, n_inputs);
      if (fmu.do_step(fmu.c, t, kStep, fmi3True, &event, &terminate, &early, &last) != fmi3OK) {
        state.SkipWithError("fmi3DoStep failed");
        return;
      }
      fmu.get_float64(fmu.c, &out, 1, &force, 1);
      t += kStep;
    }
    benchmark::DoNotOptimize(force);
  }
  state.counters["ns_per_step"] = benchmark::Counter(static_cast<double>(state.iterations()) * kSteps,
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert, benchmark::Counter::kIs1000);
}

void BM_Fmi3_SpecimenD_Held(benchmark::State& s) { fmi3_steps(s, "specimen_d.rheo", "specimen_d", false); }
void BM_Fmi3_SpecimenD_Ramp(benchmark::State& s) { fmi3_steps(s, "specimen_d.rheo", "specimen_d", true); }
void BM_Fmi3_Hydrobushing_Held(benchmark::State& s) { fmi3_steps(s, "hydrobushing.rheo", "hydrobushing", false); }
void BM_Fmi3_Hydrobushing_Ramp(benchmark::State& s) { fmi3_steps(s, "hydrobushing.rheo", "hydrobushing", true); }

}  // namespace

BENCHMARK(BM_Fmi3_SpecimenD_Held)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Fmi3_SpecimenD_Ramp)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Fmi3_Hydrobushing_Held)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Fmi3_Hydrobushing_Ramp)->Unit(benchmark::kMillisecond);
