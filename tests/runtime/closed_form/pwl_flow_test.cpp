// The modal flow of a mode (pwl_flow.cpp) against an independent path: Eigen's Pade matrix
// exponential of the augmented matrix, for the propagation and for the phased force integral
// (the last column of the exponential of [[A + i w, w0], [0, 0]] h) and for the sensitivities'
// propagation, in modes that are diagonalisable, drift (a slipping dashpot: lambda = 0) or carry
// an undamped mass at resonance; a conjugate pair's second coordinate taken as the first's
// conjugate (PwlModalWeights).
#include "runtime/closed_form/pwl_mode.hpp"

#include "support.hpp"

#include <doctest/doctest.h>
#include <unsupported/Eigen/MatrixFunctions>

#include <complex>
#include <numbers>

namespace pwl_flow_test {

using namespace rheo;

namespace {

using Complex = std::complex<double>;

void check_flow(const runtime::PwlModeSystem& s) {
  Eigen::VectorXd w = Eigen::VectorXd::LinSpaced(s.dim, -0.7, 1.3);
  w[s.one()] = 1.0, w[s.sine()] = 0.6, w[s.cosine()] = 0.8;
  const double period = 2.0 * std::numbers::pi / s.drive_omega;
  for (double tau : {1e-6 * period, period / 64.0, 0.37 * period}) {
    const Eigen::VectorXd reference = (s.A * tau).exp() * w;
    CAPTURE(tau);
    CHECK((s.advance(tau, w) - reference).cwiseAbs().maxCoeff() <= 1e-10 * (1.0 + reference.cwiseAbs().maxCoeff()));
    CHECK((s.propagator(tau) * w - reference).cwiseAbs().maxCoeff() <= 1e-10 * (1.0 + reference.cwiseAbs().maxCoeff()));
    Eigen::MatrixXcd augmented = Eigen::MatrixXcd::Zero(s.dim + 1, s.dim + 1);
    augmented.topLeftCorner(s.dim, s.dim) = s.A.cast<Complex>();
    augmented.topLeftCorner(s.dim, s.dim).diagonal().array() += Complex(0.0, s.drive_omega);
    augmented.topRightCorner(s.dim, 1) = w.cast<Complex>();
    const Eigen::MatrixXcd E = (augmented * tau).exp();
    const Complex integral = (s.force.cast<Complex>() * E.col(s.dim).head(s.dim)).value();
    CHECK(std::abs(s.phased_force_integral(tau, w) - integral) <= 1e-10 * (1e-12 + std::abs(integral)));
    // Sensitivities dw/dX0 (rows one, s and c zero, the held rows not): propagate() against the
    // exponential's product.
    runtime::PwlMatrix S = runtime::PwlMatrix::Zero(s.dim, 3);
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < s.nz + s.nh; ++r) S(r, c) = std::sin(1.0 + r + 3.0 * c);
    const Eigen::MatrixXd carried = (s.A * tau).exp() * S;
    s.propagate(tau, S);
    CHECK((S - carried).cwiseAbs().maxCoeff() <= 1e-10 * (1.0 + carried.cwiseAbs().maxCoeff()));
  }
  // The Taylor nudge: where it accepts a step it equals the exponential to rounding; steps of
  // a Newton iteration's size are accepted, a grid step's (T/64) or longer declined (for these
  // modes ||A^2||^(1/2) T/64 > 0.05), the output then untouched.
  const Eigen::VectorXd w1 = (s.A * (0.1 * period)).exp() * w;
  for (double delta : {1e-12 * period, -3e-9 * period, 1e-6 * period, -1e-4 * period, period / 64.0, 0.37 * period}) {
    const Eigen::VectorXd reference = (s.A * delta).exp() * w1;
    runtime::PwlVector out = runtime::PwlVector::Constant(s.dim, 7.0);
    const bool accepted = s.nudge(delta, w1, out);
    CAPTURE(delta);
    CHECK(accepted == (std::abs(delta) * s.reach_squared <= 0.05));
    if (std::abs(delta) <= 1e-6 * period) CHECK(accepted);
    if (std::abs(delta) >= period / 64.0) CHECK_FALSE(accepted);
    if (accepted) CHECK((out - reference).cwiseAbs().maxCoeff() <= 1e-14 * reference.cwiseAbs().maxCoeff());
    else CHECK(out == runtime::PwlVector::Constant(s.dim, 7.0));
  }
}

runtime::PwlBranch branch_of(const char* source) {
  const auto net = test::network_from(source, "m");
  runtime::PwlBranch branch;
  REQUIRE(runtime::PwlBranch::build(net, net.topology().subtrees[0], branch));
  return branch;
}

}  // namespace

TEST_CASE("the modal flow equals the matrix exponential: a damped mass behind a slider, stuck and slipping") {
  const auto branch = branch_of(
      "model m { series f { slider cap (fy = 60 N)\n spring k1 (k = 600 N/mm)\n"
      " parallel y { inerter column (b = 40 kg)\n dashpot channel (c = 3.0 N*s/mm)\n spring bulge (k = 150 N/mm) } } }");
  for (int code : {0, 1, -1}) {
    runtime::PwlModeSystem s;
    REQUIRE(runtime::build_pwl_mode(branch, runtime::PwlModeCode{static_cast<std::int8_t>(code)}, 2.0 * std::numbers::pi * 13.0, s));
    CHECK(s.modal);
    // The column's mass gives one conjugate pair: the flows form its first coordinate only
    // (PwlModalWeights), V^-1's rows exactly conjugate.
    REQUIRE(s.nz == 2);
    CHECK(s.lambda[0].imag() > 0.0);
    CHECK(s.lambda[1] == std::conj(s.lambda[0]));
    CHECK(s.weight[0] == 2);
    CHECK(s.weight[1] == 0);
    CHECK(s.V_inverse.row(1) == s.V_inverse.row(0).conjugate());
    check_flow(s);
  }
}

TEST_CASE("the modal flow equals the matrix exponential where a slipping dashpot drifts (lambda = 0)") {
  const auto branch = branch_of("model m { series arm { slider s (fy = 45 N)\n maxwell x (k = 300 N/mm, tau = 20 ms) } }");
  runtime::PwlModeSystem s;
  REQUIRE(runtime::build_pwl_mode(branch, runtime::PwlModeCode{1}, 2.0 * std::numbers::pi * 5.0, s));
  REQUIRE(s.modal);
  CHECK(std::abs(s.lambda[0]) < 1e-12);
  CHECK(s.weight[0] == 1);  // a real eigenvalue
  check_flow(s);
}

TEST_CASE("the modal flow equals the matrix exponential for an undamped mass driven at its resonance") {
  // k / b = (2 pi 10 Hz)^2: the stuck mode's eigenvalues are the drive's +-i w.
  const double b = 1000.0 / (4.0 * std::numbers::pi * std::numbers::pi * 100.0);  // kg for k = 1000 N/mm (internal: N s^2/mm)
  const std::string source = "model m { series f { slider s (fy = 1e6 N)\n spring k (k = 1000 N/mm)\n inerter i (b = " + std::to_string(b * 1000.0) +
                             " kg) } }";
  const auto branch = branch_of(source.c_str());
  runtime::PwlModeSystem s;
  REQUIRE(runtime::build_pwl_mode(branch, runtime::PwlModeCode{0}, 2.0 * std::numbers::pi * 10.0, s));
  REQUIRE(s.modal);
  check_flow(s);
}

}  // namespace pwl_flow_test
