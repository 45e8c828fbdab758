// Histories of the elements for effects that are not odd or not centred (issue 24): a friction
// element and a slider with one-sided yield forces, a polynomial spring with an even power and
// a gap whose play is off-centre, against hand solutions, on the fixed-step path and on IDA,
// in the model's parallel body and inside series chains.
#include "runtime/protocols/run_history.hpp"

#include "runtime/network/leaf_kernels.hpp"
#include "support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace run_history_test {

using namespace rheo;
using lang::SolverChoice;

namespace {

// The loop of an elastoplastic branch of stiffness k slipping at F = fy_pos and F = -fy_neg,
// by hand: from rest F = clamp(k u, -fy_neg, fy_pos) until the first turning point, then from
// each turning point (u_t, F_t) F = clamp(F_t + k (u - u_t), -fy_neg, fy_pos). The drive's
// turning points are samples (quasistatic_sine samples its peaks).
std::vector<double> hand_loop(const std::vector<double>& u, double k, double fy_pos, double fy_neg) {
  std::vector<double> f(u.size(), 0.0);
  double u_turn = 0.0, f_turn = 0.0;
  for (std::size_t j = 1; j < u.size(); ++j) {
    if (j >= 2 && (u[j] - u[j - 1]) * (u[j - 1] - u[j - 2]) < 0.0) u_turn = u[j - 1], f_turn = f[j - 1];
    f[j] = std::clamp(f_turn + k * (u[j] - u_turn), -fy_neg, fy_pos);
  }
  return f;
}

void check_force(const runtime::History& h, const std::vector<double>& expected, double tolerance, double scale) {
  REQUIRE(h.force.size() == expected.size());
  double worst = 0.0;
  for (std::size_t j = 0; j < expected.size(); ++j) worst = std::max(worst, std::abs(h.force[j] - expected[j]));
  CHECK(worst <= tolerance * scale);
}

}  // namespace

TEST_CASE("a friction element with fy_pos != fy_neg follows the one-sided loop by hand, in the body and behind a spring") {
  const runtime::Drive drive = runtime::quasistatic_sine({10.0, 4.0}, 1.0, 2, 400);
  // In the body (a one-node subtree), and in series with a spring of 4 N/mm: the chain is an
  // elastoplastic branch of stiffness 1/(1/2 + 1/4) = 4/3 N/mm with the same caps.
  const auto body = test::network_from("model m { friction f (k = 2 N/mm, fy_pos = 3 N, fy_neg = 5 N) }", "m");
  const auto chain = test::network_from("model m { series c { spring a (k = 4 N/mm)  friction f (k = 2 N/mm, fy_pos = 3 N, fy_neg = 5 N) } }", "m");
  const auto slider = test::network_from("model m { series c { spring a (k = 2 N/mm)  slider s (fy_pos = 3 N, fy_neg = 5 N) } }", "m");
  const std::vector<double> loop = hand_loop(drive.displacement, 2.0, 3.0, 5.0);
  const std::vector<double> chained = hand_loop(drive.displacement, 4.0 / 3.0, 3.0, 5.0);
  for (SolverChoice solver : {SolverChoice::fixed, SolverChoice::sundials}) {
    CAPTURE(static_cast<int>(solver));
    const double tolerance = solver == SolverChoice::fixed ? 1e-12 : 1e-5;
    check_force(runtime::run_history(body, drive, false, solver), loop, tolerance, 5.0);
    check_force(runtime::run_history(chain, drive, false, solver), chained, tolerance, 5.0);
    check_force(runtime::run_history(slider, drive, false, solver), loop, tolerance, 5.0);
  }
  // The one-sided caps are reached: +3 N at the top, -5 N at the bottom of the large cycles.
  const auto h = runtime::run_history(body, drive, false, SolverChoice::fixed);
  CHECK(*std::max_element(h.force.begin(), h.force.end()) == doctest::Approx(3.0));
  CHECK(*std::min_element(h.force.begin(), h.force.end()) == doctest::Approx(-5.0));
}

TEST_CASE("a friction element given fy_pos = fy_neg = fy is the symmetric friction element, sample for sample") {
  const runtime::Drive drive = runtime::quasistatic_sine({1.0, 0.3}, 2.0, 2, 200);
  const auto split = test::network_from("model m { spring s (k = 10 N/mm)  friction f (k = 300 N/mm, fy_pos = 40 N, fy_neg = 40 N) }", "m");
  const auto plain = test::network_from("model m { spring s (k = 10 N/mm)  friction f (k = 300 N/mm, fy = 40 N) }", "m");
  const auto a = runtime::run_history(split, drive, false, SolverChoice::fixed), b = runtime::run_history(plain, drive, false, SolverChoice::fixed);
  for (std::size_t j = 0; j < a.force.size(); ++j) CHECK(a.force[j] == doctest::Approx(b.force[j]).epsilon(1e-13));
}

TEST_CASE("a poly_spring's force is its law exactly in the body, and in series the chain's force solves F = P(u - F/k)") {
  const runtime::Drive drive = runtime::quasistatic_sine({3.0, 1.0}, 0.5, 1, 200);
  const runtime::PolyLaw law{10.0, -1.0, 0.2};  // k2^2 = 1 < 3 k1 k3 = 6: monotone
  const auto body = test::network_from("model m { poly_spring p (k1 = 10 N/mm, k2 = -1 N/mm^2, k3 = 0.2 N/mm^3) }", "m");
  const auto chain = test::network_from(
      "model m { series c { spring s (k = 50 N/mm)  poly_spring p (k1 = 10 N/mm, k2 = -1 N/mm^2, k3 = 0.2 N/mm^3) } }", "m");
  for (SolverChoice solver : {SolverChoice::fixed, SolverChoice::sundials}) {
    CAPTURE(static_cast<int>(solver));
    const auto h = runtime::run_history(body, drive, false, solver);
    for (std::size_t j = 0; j < h.force.size(); ++j) CHECK(h.force[j] == doctest::Approx(law.force(drive.displacement[j])).epsilon(1e-9));
    const auto c = runtime::run_history(chain, drive, false, solver);
    const double tolerance = solver == SolverChoice::fixed ? 1e-10 : 1e-5;
    for (std::size_t j = 0; j < c.force.size(); ++j) {
      const double f = c.force[j];
      CHECK(std::abs(f - law.force(drive.displacement[j] - f / 50.0)) <= tolerance * (1.0 + std::abs(f)));
    }
    // Relaxed at -2 mm (sample 0 is the static equilibrium there).
    const auto r = runtime::run_history(chain, runtime::Drive{{0.0, 1.0}, {-2.0, -2.0}}, false, solver);
    CHECK(std::abs(r.force[0] - law.force(-2.0 - r.force[0] / 50.0)) <= 1e-9 * std::abs(r.force[0]));
    CHECK(r.force[0] < 0.0);
    // Not odd: the force at +3 mm and at -3 mm differ by 2 k2 u^2 = -18 N.
    CHECK(law.force(3.0) + law.force(-3.0) == doctest::Approx(-18.0));
  }
}

TEST_CASE("a spring behind an off-centre gap touches at e = center +- width/2, by hand, from rest and from a relaxed start") {
  // Play [-0.2, 0.8] mm: contact at u = 0.8 mm in tension and at u = -0.2 mm in compression.
  const auto net = test::network_from("model m { series c { gap g (width = 1 mm, center = 0.3 mm)  spring s (k = 100 N/mm) } }", "m");
  auto hand = [](double u) { return 100.0 * (std::max(0.0, u - 0.8) + std::min(0.0, u + 0.2)); };
  const runtime::Drive drive = runtime::static_triangle({2.0, 0.5}, 1.0, 1, 400);
  for (SolverChoice solver : {SolverChoice::fixed, SolverChoice::sundials}) {
    CAPTURE(static_cast<int>(solver));
    const auto h = runtime::run_history(net, drive, false, solver);
    std::vector<double> expected;
    for (double u : drive.displacement) expected.push_back(hand(u));
    check_force(h, expected, solver == SolverChoice::fixed ? 1e-12 : 1e-6, 100.0);
    for (double u0 : {1.5, -1.0, 0.5}) {
      CAPTURE(u0);
      const runtime::Drive from{{0.0, 1.0, 2.0}, {u0, u0 + 0.1, u0 - 0.1}};
      const auto r = runtime::run_history(net, from, false, solver);
      for (std::size_t j = 0; j < 3; ++j) CHECK(r.force[j] == doctest::Approx(hand(from.displacement[j])).epsilon(1e-6).scale(1.0));
    }
  }
}

// The sample convention (docs/numerics.md "The sample convention of histories"): the force at
// sample j is the force at t_j at the end of the step from t_{j-1}, with the rates of the piece
// ending there; the same on both integrators. Uneven samples and a pause tell a convention that
// looks one piece ahead (or averages) from this one.
TEST_CASE("sample convention: a lone dashpot reports c (u_j - u_j-1)/(t_j - t_j-1) and a spring k u_j on both integrators") {
  const runtime::Drive drive{{0.0, 0.001, 0.003, 0.004, 0.0045, 0.007, 0.008, 0.010}, {0.0, 0.02, 0.05, 0.05, 0.03, -0.04, -0.01, 0.0}};
  const double c = 0.119303, k = 85.6;
  const auto dashpot = test::network_from(fmt::format("model m {{ dashpot d (c = {} N*s/mm) }}", c), "m");
  const auto spring = test::network_from(fmt::format("model m {{ spring s (k = {} N/mm) }}", k), "m");
  for (const SolverChoice solver : {SolverChoice::fixed, SolverChoice::sundials}) {
    const std::string name(lang::word_of(solver));
    CAPTURE(name);
    const runtime::History d = runtime::run_history(dashpot, drive, true, solver);
    const runtime::History s = runtime::run_history(spring, drive, true, solver);
    CHECK(d.force[0] == 0.0);
    for (std::size_t j = 1; j < drive.time.size(); ++j) {
      CAPTURE(j);
      const double rate = (drive.displacement[j] - drive.displacement[j - 1]) / (drive.time[j] - drive.time[j - 1]);
      CHECK(d.force[j] == doctest::Approx(c * rate).epsilon(1e-9).scale(1e-9));
      CHECK(d.element_force[0][j] == doctest::Approx(c * rate).epsilon(1e-9).scale(1e-9));
      CHECK(s.force[j] == doctest::Approx(k * drive.displacement[j]).epsilon(1e-9).scale(1e-9));
    }
  }
}

TEST_CASE("HistoryForceStream hands out history_force bit for bit, in blocks of any size, on fixed steps and on IDA") {
  const runtime::Network network = test::network_from(
      "model m { spring s (k = 120) maxwell x (k = 60, tau = 5 ms) friction f (k = 80, uy = 0.1 mm) }", "m");
  runtime::Drive from_rest = runtime::quasistatic_sine({1.0, 0.3}, 2.0, 1, 400), away = from_rest;
  for (double& u : away.displacement) u += 0.25;  // a relaxed start at 0.25 mm
  for (const runtime::Drive& drive : {from_rest, away})
    for (const SolverChoice solver : {SolverChoice::fixed, SolverChoice::sundials}) {
      const std::vector<double> whole = runtime::history_force(network, drive, solver);
      for (const std::size_t block : {std::size_t{1}, std::size_t{7}, std::size_t{5000}}) {
        CAPTURE(block);
        runtime::HistoryForceStream stream(network, drive, solver);
        std::vector<double> streamed, piece(block);
        for (std::size_t count = 0; (count = stream.next(piece)) > 0;)
          streamed.insert(streamed.end(), piece.begin(), piece.begin() + static_cast<long>(count));
        REQUIRE(streamed.size() == whole.size());
        CHECK(std::equal(streamed.begin(), streamed.end(), whole.begin()));
      }
    }
}

}  // namespace run_history_test
