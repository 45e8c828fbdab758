// Newton's method on the map of a followed cycle's sequence of switches (pwl_cycle.hpp,
// Run::replay; pwl_periodic.cpp): the shooting then follows about two cycles a slipping point
// (one for the sequence and its sensitivities, one that closes), and reaches the periodic
// states the plain shooting reaches (a cycle followed per Newton step).
#include "runtime/closed_form/pwl_periodic.hpp"
#include "runtime/io/fit_data.hpp"
#include "lang/frontend.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace pwl_replay_test {

using namespace rheo;

namespace {

struct GridCycles {
  double replayed = 0.0, plain = 0.0;  // cycles a point
};

// Every point of the example's grid on the event-driven subtree of the example's model, solved
// cold with and without replays: their K'_1 and K''_1 agree within TOLERANCE of |K*|; returns
// the cycles a point of each.
GridCycles compare_grid(const std::string& file, const std::string& model, const std::string& csv, double tolerance) {
  const lang::Program program = lang::load_program(std::string(RHEO_EXAMPLES_DIR) + "/" + file);
  const lang::CheckedModel* checked = program.find_model(model);
  REQUIRE(checked != nullptr);
  const runtime::Network net = runtime::Network::compile(*checked);
  runtime::PwlBranch branch;
  int event_driven = 0;
  for (int root : net.topology().subtrees) {
    const runtime::TreeNode& node = net.topology().nodes[static_cast<std::size_t>(root)];
    if (!node.linear && node.child_count > 0 && runtime::PwlBranch::build(net, root, branch)) ++event_driven;
  }
  REQUIRE(event_driven == 1);
  const runtime::HarmonicData grid = runtime::read_fit_data(std::string(RHEO_DATA_DIR) + "/" + csv, 1.0).harmonic();
  runtime::PwlPeriodicState replayed, plain(false);
  GridCycles cycles;
  double worst = 0.0;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const double u0 = grid.amplitude[i], omega = 2.0 * std::numbers::pi * grid.frequency[i];
    REQUIRE(replayed.solve(branch, u0, omega));
    REQUIRE(plain.solve(branch, u0, omega));
    cycles.replayed += replayed.cycles(), cycles.plain += plain.cycles();
    CAPTURE(u0);
    CAPTURE(grid.frequency[i]);
    const double scale = std::hypot(plain.storage(), plain.loss());
    const double difference = std::max(std::abs(replayed.storage() - plain.storage()), std::abs(replayed.loss() - plain.loss())) / scale;
    CHECK(difference < tolerance);
    worst = std::max(worst, difference);
  }
  MESSAGE(csv << ": K'_1 and K''_1 within " << worst << " of |K*|");
  cycles.replayed /= static_cast<double>(grid.size()), cycles.plain /= static_cast<double>(grid.size());
  return cycles;
}

}  // namespace

TEST_CASE("the fluid column's grid: two cycles a slipping point, the plain shooting's periodic states") {
  // examples/hydrobushing_fit.rheo block 2's slider-capped fluid branch at its start values on
  // the example's 147 points (18 never slip: one cycle each). The plain shooting follows 3.41
  // cycles a point.
  const GridCycles cycles = compare_grid("hydrobushing_fit.rheo", "coupled", "hydrobushing_harmonic.csv", 1e-11);
  MESSAGE("fluid column: " << cycles.replayed << " cycles a point, plain " << cycles.plain);
  CHECK(cycles.plain > 3.0);
  CHECK(cycles.replayed < 2.5);
}

TEST_CASE("a slider before a Maxwell arm: the plain shooting's periodic states, in no more cycles") {
  // examples/coupled_bushing_fit.rheo's nested arm at its start values.
  const GridCycles cycles = compare_grid("coupled_bushing_fit.rheo", "coupled", "coupled_bushing_harmonic.csv", 1e-11);
  MESSAGE("slider and Maxwell arm: " << cycles.replayed << " cycles a point, plain " << cycles.plain);
  CHECK(cycles.replayed <= cycles.plain);
}

}  // namespace pwl_replay_test
