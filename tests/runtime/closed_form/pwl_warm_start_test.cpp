// Warm starts of the event path's shooting (pwl_warm_start.hpp): a column of a differenced
// Jacobian started from the base point's periodic states reaches the periodic state the cold
// start reaches, to the shooting's tolerance, in fewer cycles (or no more); a column that leaves the subtree
// unchanged gets the base's bits; and the results do not depend on the thread count.
#include "runtime/closed_form/pwl_warm_start.hpp"
#include "runtime/core/evaluation_context.hpp"
#include "runtime/fit/objective.hpp"
#include "runtime/io/fit_data.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

namespace pwl_warm_start_test {

using namespace rheo;

namespace {

runtime::Network example_network(const std::string& file, const std::string& name) {
  const lang::Program program = lang::load_program(std::string(RHEO_EXAMPLES_DIR) + "/" + file);
  const lang::CheckedModel* model = program.find_model(name);
  REQUIRE(model != nullptr);
  return runtime::Network::compile(*model);
}

runtime::HarmonicData example_grid(const std::string& csv) {
  return runtime::read_fit_data(std::string(RHEO_DATA_DIR) + "/" + csv, 1.0).harmonic();
}

runtime::Network moved(const runtime::Network& network, const std::string& path, double factor) {
  std::vector<double> values = network.parameters();
  values[static_cast<std::size_t>(test::parameter_index(network, path))] *= factor;
  return network.with_parameters(values);
}

std::vector<runtime::HarmonicPoint> evaluate(const runtime::Network& network, const runtime::HarmonicData& grid, int threads,
                                             const runtime::EvaluationContext& context) {
  runtime::HarmonicOptions options;
  options.threads = threads;
  const runtime::EvaluationScope scope(context);
  return runtime::simulate_at(network, grid, options);
}

int total_cycles(const std::vector<runtime::HarmonicPoint>& points) {
  int cycles = 0;
  for (const auto& p : points) cycles += p.cycles;
  return cycles;
}

// The base evaluation recorded, then columns moving each of `paths` by a relative 1e-6:
// warm against cold (in fewer cycles where FEWER, else in no more), and warm on 1 thread
// against warm on 2.
void check_columns(const runtime::Network& base, const runtime::HarmonicData& grid, const std::vector<std::string>& paths,
                   const std::vector<std::string>& outside, bool fewer) {
  runtime::PwlWarmStarts states;
  const auto base_points = evaluate(base, grid, 2, {&states, nullptr});
  states.seal();
  // One event-driven subtree: every point whose cold start did not close at once (a slider slips).
  std::size_t slipping = 0;
  for (const auto& p : base_points) slipping += p.cycles > 1;
  REQUIRE(slipping > grid.size() / 2);
  REQUIRE(states.size() == slipping);
  for (const std::string& path : paths) {
    CAPTURE(path);
    const runtime::Network column = moved(base, path, 1.0 + 1e-6);
    const auto cold = evaluate(column, grid, 1, {});
    const auto warm = evaluate(column, grid, 1, {nullptr, &states});
    const auto warm2 = evaluate(column, grid, 2, {nullptr, &states});
    for (std::size_t i = 0; i < grid.size(); ++i) {
      CAPTURE(i);
      // The shooting's tolerance is 1e-11 on the scaled state: the measures agree to far below
      // the column's own change (1e-6 relative in a parameter).
      CHECK(test::relative_error(warm[i].measures.stiffness, cold[i].measures.stiffness) < 1e-10);
      CHECK(std::abs(warm[i].measures.phase - cold[i].measures.phase) < 1e-10);
      CHECK(test::relative_error(warm[i].measures.energy, cold[i].measures.energy) < 1e-10);
      CHECK(warm[i].measures.stiffness == warm2[i].measures.stiffness);  // bitwise: the same start, whichever thread
      CHECK(warm[i].measures.phase == warm2[i].measures.phase);
    }
    if (fewer) CHECK(total_cycles(warm) < total_cycles(cold));
    else CHECK(total_cycles(warm) <= total_cycles(cold));
  }
  for (const std::string& path : paths) {  // a trial step's move, 1 %: the same periodic state as the cold start's
    CAPTURE(path);
    const runtime::Network trial = moved(base, path, 1.01);
    const auto cold = evaluate(trial, grid, 1, {});
    evaluate(base, grid, 1, {});  // another branch: this thread forgets the trial's solves
    const auto warm = evaluate(trial, grid, 1, {nullptr, &states});
    const auto cold_again = evaluate(trial, grid, 1, {});  // this thread keeps the warm solves of the branch only
    for (std::size_t i = 0; i < grid.size(); ++i) {
      CAPTURE(i);
      CHECK(test::relative_error(warm[i].measures.stiffness, cold[i].measures.stiffness) < 1e-10);
      CHECK(std::abs(warm[i].measures.phase - cold[i].measures.phase) < 1e-10);
      CHECK(cold_again[i].measures.stiffness == cold[i].measures.stiffness);  // a cold solve never restores a warm one
      CHECK(cold_again[i].measures.phase == cold[i].measures.phase);
    }
  }
  for (const std::string& path : outside) {  // the subtree unchanged: the base's bits, warm or not
    CAPTURE(path);
    const runtime::Network column = moved(base, path, 1.0 + 1e-6);
    const auto cold = evaluate(column, grid, 1, {});
    const auto warm = evaluate(column, grid, 2, {nullptr, &states});
    for (std::size_t i = 0; i < grid.size(); ++i) {
      CAPTURE(i);
      CHECK(warm[i].measures.stiffness == cold[i].measures.stiffness);
      CHECK(warm[i].measures.phase == cold[i].measures.phase);
    }
  }
}

}  // namespace

TEST_CASE("warm-started columns of the hydrobushing grid reach the cold start's periodic states in fewer cycles") {
  const runtime::Network network = example_network("hydrobushing_fit.rheo", "coupled");
  check_columns(network, example_grid("hydrobushing_harmonic.csv"), {"fluid.fy", "fluid.k1", "fluid.b", "fluid.c", "fluid.k2"}, {"m1.k"}, true);
}

// Its cold start already closes in two cycles a slipping point (one, Newton's iterations on its
// sequence of switches, then the closing one: pwl_replay_test): the warm start saves those
// iterations, not cycles.
TEST_CASE("warm-started columns of the coupled bushing reach the cold start's periodic states in no more cycles") {
  const runtime::Network network = example_network("coupled_bushing_fit.rheo", "coupled");
  check_columns(network, example_grid("coupled_bushing_harmonic.csv"), {"arm.s.fy", "arm.ma.k", "arm.ma.tau"}, {"f1.uy"}, false);
}

TEST_CASE("warm starts: records found by point and subtree once sealed, storage kept across clear") {
  runtime::PwlWarmStarts states;
  runtime::PwlStart a, b;
  a.X0 = runtime::PwlVector::Constant(2, 1.0), a.mode = {1, 0};
  b.X0 = runtime::PwlVector::Constant(2, 2.0), b.mode = {0, -1};
  states.record(2.0, 10.0, 0, a);
  states.record(1.0, 10.0, 1, b);
  states.record(1.0, 10.0, 0, a);
  CHECK(states.find(1.0, 10.0, 1) == nullptr);  // not sealed
  states.seal();
  REQUIRE(states.find(1.0, 10.0, 1) != nullptr);
  CHECK(states.find(1.0, 10.0, 1)->X0(0) == 2.0);
  CHECK(states.find(1.0, 10.0, 1)->mode == runtime::PwlModeCode{0, -1});
  CHECK(states.find(2.0, 10.0, 0)->X0(0) == 1.0);
  CHECK(states.find(2.0, 10.0, 1) == nullptr);
  CHECK(states.find(1.0, 11.0, 0) == nullptr);
  states.clear();
  CHECK(states.size() == 0);
  CHECK(states.find(2.0, 10.0, 0) == nullptr);
}

}  // namespace pwl_warm_start_test
