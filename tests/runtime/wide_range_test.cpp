// Any frequency a master curve spans (issue #25 item 6): a generalised Maxwell model with
// relaxation times from 1e-14 s to 1e12 s, one per decade, at every decade of frequency from
// 1e-20 Hz to 1e20 Hz (lang/limits.hpp's range) and amplitudes from 1e-20 mm to 1e20 mm, against
// its closed form evaluated here in long double:
//   K*(w) = k0 + sum_i k_i i w tau_i / (1 + i w tau_i).
// The closed-form paths (root Maxwell elements, nested blocks, the phasor composition and the
// thesis approximation) to 1e-12; time stepping and IDA at the extreme frequencies to the
// discretisation and integration error they have at any frequency (documented below); the
// reader over that range; a fit of the master curve recovering every stiffness; the
// event-driven path by its time and amplitude scaling invariance.
#include "runtime/closed_form/periodic_closed_form.hpp"
#include "runtime/closed_form/phasor.hpp"
#include "runtime/fit/fit.hpp"
#include "runtime/fit/thesis_approximation.hpp"
#include "runtime/io/harmonic_data.hpp"
#include "runtime/io/history_csv.hpp"
#include "runtime/network/leaf_kernels.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

namespace wide_range_test {

using namespace rheo;

namespace {

constexpr int kArms = 27;  // tau_i = 10^(i - 14) s, i = 0 ... 26
constexpr double kEquilibrium = 5.0;

double arm_tau(int i) { return std::pow(10.0, i - 14); }
double arm_k(int i) { return 10.0 * (1 + i % 5) + 0.5 * i; }  // N/mm, varied, no two neighbours alike

// The model; `free` writes every stiffness as a fit parameter started at 100 N/mm.
std::string generalised_maxwell(bool free, const std::string& wrap_first = "") {
  auto stiffness = [&](double k) { return free ? std::string("100 in [1e-6, 100000]") : fmt::format("{:.17g}", k); };
  std::string body = fmt::format("  spring k0 (k = {})\n", stiffness(kEquilibrium));
  for (int i = 0; i < kArms; ++i) {
    std::string arm = fmt::format("maxwell m{} (k = {}, tau = {:.17g} s)", i, stiffness(arm_k(i)), arm_tau(i));
    // A nested block around the first arms exercises the subtree path too.
    if (!wrap_first.empty() && i < 3) arm = fmt::format("{} w{} {{ {} spring pad (k = 1e30) }}", wrap_first, i, arm);
    body += "  " + arm + "\n";
  }
  return "model gm {\n" + body + "}\n";
}

// K* of the model in long double, independent of rheo.
std::complex<long double> exact_k_star(double frequency) {
  const long double w = 2.0L * std::numbers::pi_v<long double> * frequency;
  std::complex<long double> k{kEquilibrium, 0.0L};
  for (int i = 0; i < kArms; ++i) {
    const std::complex<long double> iwt{0.0L, w * static_cast<long double>(arm_tau(i))};
    k += static_cast<long double>(arm_k(i)) * iwt / (1.0L + iwt);
  }
  return k;
}

std::vector<double> decades(int from, int to) {
  std::vector<double> f;
  for (int j = from; j <= to; ++j) f.push_back(std::pow(10.0, j));
  return f;
}

void check_point(const runtime::HarmonicPoint& p, double stiffness_tolerance, double phase_tolerance) {
  const auto k = exact_k_star(p.frequency);
  CAPTURE(p.frequency);
  CAPTURE(p.amplitude);
  CAPTURE(p.cycles);
  CAPTURE(p.residual);
  CHECK(p.converged);
  CHECK(test::relative_error(p.measures.stiffness, static_cast<double>(std::abs(k))) <= stiffness_tolerance);
  CHECK(std::abs(p.measures.phase - static_cast<double>(std::arg(k))) <= phase_tolerance);
}

runtime::HarmonicPoint point_by(const runtime::Network& net, double u0, double f, runtime::SteadyState steady, runtime::SolverChoice solver,
                                runtime::HarmonicDefinition definition = runtime::HarmonicDefinition::thesis) {
  runtime::HarmonicOptions o;
  o.steady_state = steady;
  o.solver = solver;
  o.definition = definition;
  return runtime::simulate_harmonic_point(net, u0, f, o);
}

}  // namespace

TEST_CASE("a Maxwell element's storage and loss stay exact for omega tau from 1e-300 to 1e300") {
  for (int e = -300; e <= 300; e += 7) {
    const double x = std::pow(10.0, e) * 1.37;
    const long double xl = x;
    const auto m = runtime::maxwell_storage_loss(3.0, x);
    CAPTURE(x);
    // Below x = 1e-154 the storage k x^2 underflows double range, as it must.
    if (x > 1e-150) CHECK(test::relative_error(m.storage, static_cast<double>(3.0L * xl * xl / (1.0L + xl * xl))) < 1e-15);
    CHECK(test::relative_error(m.loss, static_cast<double>(3.0L * xl / (1.0L + xl * xl))) < 1e-15);
  }
  const auto at_rest = runtime::maxwell_storage_loss(3.0, 0.0);
  CHECK(at_rest.storage == 0.0);
  CHECK(at_rest.loss == 0.0);
}

TEST_CASE("a generalised Maxwell model with tau from 1e-14 s to 1e12 s: closed forms at every decade from 1e-20 to 1e20 Hz") {
  const auto net = test::network_from(generalised_maxwell(false), "gm");
  const auto nested = test::network_from(generalised_maxwell(false, "series"), "gm");  // three arms behind a rigid pad
  const auto model = test::model_from(generalised_maxwell(false), "gm");
  std::vector<double> values;
  for (const auto& p : model.parameters) values.push_back(p.value);
  for (double f : decades(-20, 20)) {
    for (double u0 : {1e-20, 1.0, 1e20})
      for (auto definition : {runtime::HarmonicDefinition::thesis, runtime::HarmonicDefinition::first_harmonic}) {
        check_point(point_by(net, u0, f, runtime::SteadyState::closed_form, runtime::SolverChoice::automatic, definition), 1e-12, 1e-12);
        // The pads (1e30 N/mm) shift K* of the wrapped arms by k/1e30 at most.
        check_point(point_by(nested, u0, f, runtime::SteadyState::closed_form, runtime::SolverChoice::automatic, definition), 1e-12, 1e-12);
      }
    const auto phasor = runtime::complex_stiffness(model, values, f);
    REQUIRE(phasor);
    const auto k = exact_k_star(f);
    CHECK(test::relative_error(std::abs(*phasor), static_cast<double>(std::abs(k))) <= 1e-12);
    CHECK(std::abs(std::arg(*phasor) - static_cast<double>(std::arg(k))) <= 1e-12);
    for (const auto& p : runtime::approximate_harmonic(net, {1e-20, 1e20}, {f, f})) check_point(p, 1e-12, 1e-12);
  }
}

// Time stepping (2048 steps per cycle, the exact Maxwell update under a piecewise-linear drive)
// has the same relative error at any frequency: it depends on w dt and dt/tau only, so the point
// at 1e-14 Hz is the point at 1 Hz with every tau scaled by 1e-14 (docs/numerics.md: 1e-5 for a
// generalised Maxwell model; observed here 1.3e-5 at 1e-14 Hz, where the slowest arm has
// w tau = 0.06). IDA (rtol 1e-8) lies within its harmonic tolerance of 1e-6 relative per cycle.
// Both to 3e-5 in K and 3e-5 rad. IDA starts from rest and has no skip of a slow geometric tail:
// at 1e14 Hz the arm of 1e-12 s (100 periods) would need about 750 cycles, as the same arm does
// at 1 Hz with tau = 100 s, so IDA is checked at the extremes and at 1e-14 Hz.
TEST_CASE("time stepping and IDA at extreme frequencies and amplitudes agree with the closed form") {
  const auto net = test::network_from(generalised_maxwell(false), "gm");
  for (double u0 : {1e-20, 1e20}) {
    CAPTURE(u0);
    for (double f : {1e-20, 1e-14, 1e14, 1e20})
      check_point(point_by(net, u0, f, runtime::SteadyState::time_stepping, runtime::SolverChoice::fixed), 3e-5, 3e-5);
    INFO("IDA");
    for (double f : {1e-20, 1e-14, 1e20})
      check_point(point_by(net, u0, f, runtime::SteadyState::time_stepping, runtime::SolverChoice::sundials), 3e-5, 3e-5);
  }
}

TEST_CASE("the event-driven periodic state is invariant under scaling time and amplitude by 1e19") {
  // K(u0, f; uy, tau) = K(s u0, r f; s uy, tau / r): forces scale with s, times with 1/r.
  auto network = [](double uy, double tau) {
    return test::network_from(fmt::format("model m {{ spring s (k = 50) series arm {{ friction f (k = 100, uy = {:.17g} mm) "
                                          "maxwell x (k = 200, tau = {:.17g} s) }} }}",
                                          uy, tau),
                              "m");
  };
  REQUIRE_FALSE(runtime::has_closed_form_periodic_state(network(0.3, 0.05), false));  // the event-driven path, not a root closed form
  REQUIRE(runtime::has_closed_form_periodic_state(network(0.3, 0.05), true));
  const auto reference = runtime::closed_form_harmonic_point(network(0.3, 0.05), 1.0, 1.0, runtime::HarmonicDefinition::thesis);
  for (double s : {1e-19, 1e19})
    for (double r : {1e-19, 1e19}) {
      const auto scaled = runtime::closed_form_harmonic_point(network(0.3 * s, 0.05 / r), s, r, runtime::HarmonicDefinition::thesis);
      CAPTURE(s);
      CAPTURE(r);
      CHECK(test::relative_error(scaled.measures.stiffness, reference.measures.stiffness) < 1e-9);
      CHECK(std::abs(scaled.measures.phase - reference.measures.phase) < 1e-9);
    }
}

namespace {

// The model's master curve at `per_decade` frequencies per decade over [1e-20, 1e20] Hz, 0.1 mm.
std::string master_curve_csv(int per_decade) {
  std::string text = "amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n";
  for (int j = -20 * per_decade; j <= 20 * per_decade; ++j) {
    const double f = std::pow(10.0, static_cast<double>(j) / per_decade);
    const auto k = exact_k_star(f);
    text += fmt::format("0.1,{:.17g},{:.17g},{:.17g}\n", f, static_cast<double>(std::abs(k)),
                        static_cast<double>(std::arg(k)) * 180.0 / std::numbers::pi);
  }
  return text;
}

}  // namespace

TEST_CASE("the reader takes a master curve from 1e-20 to 1e20 Hz and a fit recovers every stiffness of it") {
  const auto data = runtime::harmonic_data_from_table(runtime::parse_table("master.csv", master_curve_csv(3)));
  REQUIRE(data.size() == 121);
  CHECK(data.frequency.front() == 1e-20);
  CHECK(data.frequency.back() == 1e20);
  CHECK(test::relative_error(data.stiffness.back(), static_cast<double>(std::abs(exact_k_star(1e20)))) < 1e-15);

  const auto start = test::network_from(generalised_maxwell(true), "gm");
  runtime::FitSettings settings;
  settings.statistics = false;
  const std::vector<runtime::FitDataSet> sets{runtime::FitDataSet{"master.csv", 1.0, data}};
  const auto result = runtime::fit(start, runtime::bounded_parameters(start), sets, settings);
  CHECK(result.err < 1e-10);
  CHECK(result.network.parameter(test::parameter_index(start, "k0.k")) == doctest::Approx(kEquilibrium).epsilon(1e-6));
  for (int i = 0; i < kArms; ++i) {
    CAPTURE(i);
    CHECK(result.network.parameter(test::parameter_index(start, fmt::format("m{}.k", i))) == doctest::Approx(arm_k(i)).epsilon(1e-6));
  }
}

}  // namespace wide_range_test
