// DaeHistoryStepper (a history through IDA a sample at a time, in a window of the drive) against
// DaeIntegrator run on the whole drive at once, the independent path it replaces: the same forces
// and element outputs bit for bit, from rest and from a relaxed start, with a slider that slips
// and sticks, an inerter, uneven sampling, and a network IDA has no unknown for. And its scales
// sample by sample against those of the whole drive.
#include "runtime/dae/dae_history_stepper.hpp"

#include "runtime/dae/dae_protocols.hpp"
#include "runtime/stepping/relaxed_state.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <optional>

namespace dae_history_stepper_test {

using namespace rheo;

namespace {

bool bitwise(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every sample's force and element forces, IDA on the whole drive (as dae_history ran it before
// the stepper): one start, then advance() to each sample.
struct Run {
  std::vector<double> force, element_force;
};

Run whole(const runtime::Network& network, const runtime::Drive& drive, const runtime::StartAtRest* start) {
  const runtime::DaeGraph graph = runtime::DaeGraph::build(network);
  double reach = 0.0;
  for (double u : drive.displacement) reach = std::max(reach, std::abs(u));
  const double length = std::max(reach, 1e-6), duration = drive.time.back() - drive.time.front();
  runtime::DaeOptions dae;
  dae.relative_tolerance = runtime::kDaeRelativeTolerance;
  dae.length_scale = length;
  dae.velocity_scale = length / duration;
  dae.force_scale = runtime::dae_force_scale(network, length, dae.velocity_scale);
  dae.newton_tolerance = runtime::dae_newton_tolerance(graph, length, dae.force_scale);
  runtime::DaeIntegrator integrator(graph, dae);
  const runtime::DriveSignal signal{runtime::DriveSignal::Kind::samples, 0.0, 0.0, &drive};
  std::optional<std::vector<double>> positions;
  if (start) positions = runtime::dae_start_positions(network, graph, drive.displacement.front(), *start);
  integrator.start(signal, positions ? &*positions : nullptr);
  Run run;
  std::vector<double> f, e;
  for (std::size_t k = 1; k < drive.time.size(); ++k) {
    run.force.push_back(integrator.advance(drive.time[k]));
    integrator.element_outputs(f, e);
    run.element_force.insert(run.element_force.end(), f.begin(), f.end());
  }
  return run;
}

Run stepped(const runtime::Network& network, const runtime::Drive& drive, const runtime::StartAtRest* start) {
  runtime::DaeHistoryStepper stepper(network, true, runtime::DaeHistoryScales::of(drive));
  stepper.start(drive.time[0], drive.displacement[0], start);
  Run run;
  for (std::size_t k = 1; k < drive.time.size(); ++k) {
    run.force.push_back(stepper.step(drive.time[k], drive.displacement[k]));
    run.element_force.insert(run.element_force.end(), stepper.element_force().begin(), stepper.element_force().end());
  }
  return run;
}

// A two-sine drive from U0 [mm] with uneven sampling (every seventh interval 2.5 times longer).
runtime::Drive uneven_drive(double u0, int samples) {
  runtime::Drive d{{0.0}, {u0}};
  double t = 0.0;
  for (int k = 1; k < samples; ++k) {
    t += k % 7 == 0 ? 2.5e-3 : 1e-3;
    d.time.push_back(t);
    d.displacement.push_back(u0 + 1.5 * std::sin(2.0 * 3.0 * t * 3.14159) + 0.1 * std::sin(2.0 * 40.0 * t * 3.14159));
  }
  return d;
}

}  // namespace

TEST_CASE("a history through IDA a sample at a time gives the whole-drive integration's numbers bit for bit") {
  const runtime::Network network = test::network_from(R"(model m {
  spring rubber (k = 800 N/mm)
  maxwell visco (k = 150 N/mm, tau = 3 ms)
  series fluid { slider cap (fy = 60 N)  spring k1 (k = 600 N/mm)
    parallel y { inerter column (b = 40 kg)  dashpot channel (c = 3 N*s/mm)  spring bulge (k = 150 N/mm) } }
})",
                                                      "m");
  for (const double u0 : {0.0, 0.4}) {
    CAPTURE(u0);
    const runtime::Drive drive = uneven_drive(u0, 700);
    std::optional<runtime::StartAtRest> start;
    if (u0 != 0.0) start = runtime::relaxed_start(network, runtime::relaxed_state(network, u0));
    const Run a = whole(network, drive, start ? &*start : nullptr), b = stepped(network, drive, start ? &*start : nullptr);
    REQUIRE(a.force.size() == b.force.size());
    REQUIRE(a.element_force.size() == b.element_force.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.force.size(); ++i) differ += !bitwise(a.force[i], b.force[i]);
    for (std::size_t i = 0; i < a.element_force.size(); ++i) differ += !bitwise(a.element_force[i], b.element_force[i]);
    CHECK(differ == 0);
    double cap = 0.0;  // the slider carries its full 60 N: it slips
    for (std::size_t i = 2; i < a.element_force.size(); i += 7) cap = std::max(cap, std::abs(a.element_force[i]));
    CHECK(cap == doctest::Approx(60.0).epsilon(1e-6));
  }
  // Springs and a dashpot only: IDA has no unknown, and the stepper follows the drive alone.
  const runtime::Network plain = test::network_from("model m { spring s (k = 3 N/mm) dashpot d (c = 0.5 N*s/mm) }", "m");
  const runtime::Drive drive = uneven_drive(0.0, 50);
  const Run a = whole(plain, drive, nullptr), b = stepped(plain, drive, nullptr);
  REQUIRE(a.force.size() == b.force.size());
  for (std::size_t i = 0; i < a.force.size(); ++i) CHECK(bitwise(a.force[i], b.force[i]));
}

TEST_CASE("DaeHistoryScales sample by sample are those of the whole drive") {
  const runtime::Drive drive = uneven_drive(0.3, 90);
  runtime::DaeHistoryScales added;
  for (std::size_t k = 0; k < drive.time.size(); ++k) added.add(drive.time[k], drive.displacement[k]);
  const runtime::DaeHistoryScales of = runtime::DaeHistoryScales::of(drive);
  CHECK(bitwise(added.reach, of.reach));
  CHECK(bitwise(added.duration, of.duration));
  CHECK(of.duration == drive.time.back());
  double reach = 0.0;
  for (double u : drive.displacement) reach = std::max(reach, std::abs(u));
  CHECK(of.reach == reach);
}

}  // namespace dae_history_stepper_test
