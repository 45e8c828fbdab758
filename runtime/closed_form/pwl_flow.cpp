// The exact flow of a mode of a piecewise-linear branch (pwl_mode.hpp): modal closed forms,
// or the matrix exponential where the state block is defective.
#include "runtime/closed_form/pwl_mode.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <unsupported/Eigen/MatrixFunctions>

#include <cmath>

namespace rheo::runtime {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXcd;
using Eigen::VectorXd;
using Complex = std::complex<double>;

// M_k(z, h) = int_0^h tau^k e^{z tau} dtau: by its power series where |z h| <= 4, otherwise by
// M_0 = (e^{zh} - 1)/z and M_k = (h^k e^{zh} - k M_{k-1})/z (stable there; Re z <= 0 for the
// passive networks here, so nothing overflows).
Complex moment(int k, Complex z, double h) {
  const Complex zh = z * h;
  if (std::norm(zh) <= 16.0) {
    Complex term = std::pow(h, k + 1), sum = term / static_cast<double>(k + 1);
    for (int n = 1; n < 60; ++n) {
      term *= zh / static_cast<double>(n);
      const Complex add = term / static_cast<double>(n + k + 1);
      sum += add;
      if (std::norm(add) <= 1e-34 * std::norm(sum)) break;
    }
    return sum;
  }
  const Complex e = std::exp(zh);
  Complex m = (e - 1.0) / z;
  for (int j = 1; j <= k; ++j) m = (std::pow(h, j) * e - static_cast<double>(j) * m) / z;
  return m;
}

// P(lambda, mu, tau) = int_0^tau e^{lambda (tau - s)} e^{mu s} ds = (e^{mu tau} - e^{lambda tau})/(mu - lambda),
// tau e^{lambda tau} at mu = lambda.
Complex response(Complex lambda, Complex mu, double tau) {
  const Complex d = mu - lambda;
  if (std::norm(d) * tau * tau >= 1e-6) return (std::exp(mu * tau) - std::exp(lambda * tau)) / d;
  const Complex dt = d * tau;
  return std::exp(lambda * tau) * tau * (1.0 + dt * (0.5 + dt * (1.0 / 6.0 + dt * (1.0 / 24.0 + dt / 120.0))));
}

// int_0^h P(lambda, mu, tau) e^{i w tau} dtau.
Complex phased_response(Complex lambda, Complex mu, double omega, double h) {
  const Complex d = mu - lambda, a = lambda + Complex(0.0, omega);
  if (std::norm(d) * h * h >= 1e-6) return (moment(0, mu + Complex(0.0, omega), h) - moment(0, a, h)) / d;
  // (e^{d tau} - 1)/d = sum_k d^{k-1} tau^k / k!, to k = 5 (truncation below 1e-17 here).
  Complex sum = 0.0, power = 1.0;
  double factorial = 1.0;
  for (int k = 1; k <= 5; ++k) {
    factorial *= k;
    sum += power / factorial * moment(k, a, h);
    power *= d;
  }
  return sum;
}

}  // namespace

void PwlModeSystem::decompose() {
  modal = false;
  if (nz > 0) {
    const MatrixXd Azz = A.topLeftCorner(nz, nz);
    Eigen::EigenSolver<MatrixXd> eig(Azz);
    if (eig.info() != Eigen::Success) return;
    Eigen::FullPivLU<Eigen::MatrixXcd> lu(eig.eigenvectors());
    if (!(lu.rcond() > 1e-8)) return;
    V = eig.eigenvectors();
    lambda = eig.eigenvalues();
    V_inverse = lu.inverse();
    const double error = (V * lambda.asDiagonal() * V_inverse - Azz.cast<Complex>()).cwiseAbs().maxCoeff();
    if (!(error <= 1e-11 * std::max(Azz.cwiseAbs().maxCoeff(), 1e-300))) return;
  } else {
    V.resize(0, 0), V_inverse.resize(0, 0), lambda.resize(0);
  }
  phi = V_inverse * A.block(0, nz, nz, nh + 1).cast<Complex>();
  const Eigen::VectorXcd a_c = A.col(cosine()).head(nz).cast<Complex>(), a_s = A.col(sine()).head(nz).cast<Complex>();
  g_plus = 0.5 * (V_inverse * (a_c - Complex(0.0, 1.0) * a_s));
  g_minus = 0.5 * (V_inverse * (a_c + Complex(0.0, 1.0) * a_s));
  force_V = force.head(nz).cast<Complex>() * V;
  modal = true;
}

// The modal factors of a flow over tau: e^{lambda tau} and P(lambda, mu, tau) for mu = 0, i w, -i w.
struct ModalFactors {
  VectorXcd decay, constant, plus, minus;
  double cos_step = 1.0, sin_step = 0.0;
};

ModalFactors modal_factors(const PwlModeSystem& s, double tau) {
  ModalFactors f;
  const Complex i_omega(0.0, s.drive_omega);
  f.decay.resize(s.nz), f.constant.resize(s.nz), f.plus.resize(s.nz), f.minus.resize(s.nz);
  for (int j = 0; j < s.nz; ++j) {
    const Complex l = s.lambda[j];
    f.decay[j] = std::exp(l * tau);
    f.constant[j] = response(l, 0.0, tau);
    f.plus[j] = s.g_plus[j] * response(l, i_omega, tau);
    f.minus[j] = s.g_minus[j] * response(l, -i_omega, tau);
  }
  f.cos_step = std::cos(s.drive_omega * tau), f.sin_step = std::sin(s.drive_omega * tau);
  return f;
}

VectorXd PwlModeSystem::advance(double tau, const VectorXd& w) const {
  if (tau == 0.0) return w;
  if (!modal) return (A * tau).exp() * w;
  const ModalFactors f = modal_factors(*this, tau);
  VectorXd out = w;
  const double s0 = w[sine()], c0 = w[cosine()];
  const Complex E(c0, s0);
  if (nz > 0) {
    const VectorXcd q = f.decay.cwiseProduct(V_inverse * w.head(nz).cast<Complex>()) +
                        f.constant.cwiseProduct(phi * w.segment(nz, nh + 1).cast<Complex>()) + E * f.plus + std::conj(E) * f.minus;
    out.head(nz) = (V * q).real();
  }
  out[sine()] = s0 * f.cos_step + c0 * f.sin_step;
  out[cosine()] = c0 * f.cos_step - s0 * f.sin_step;
  return out;
}

MatrixXd PwlModeSystem::propagator(double tau) const {
  if (!modal) return (A * tau).exp();
  const ModalFactors f = modal_factors(*this, tau);
  MatrixXd P = MatrixXd::Identity(dim, dim);
  if (nz > 0) {
    P.topLeftCorner(nz, nz) = (V * f.decay.asDiagonal() * V_inverse).real();
    P.block(0, nz, nz, nh + 1) = (V * f.constant.asDiagonal() * phi).real();
    const Complex i(0.0, 1.0);
    P.col(sine()).head(nz) = (V * (i * f.plus - i * f.minus)).real();  // E = i
    P.col(cosine()).head(nz) = (V * (f.plus + f.minus)).real();        // E = 1
  }
  P(sine(), sine()) = f.cos_step, P(sine(), cosine()) = f.sin_step;
  P(cosine(), sine()) = -f.sin_step, P(cosine(), cosine()) = f.cos_step;
  return P;
}

Complex PwlModeSystem::phased_force_integral(double h, const VectorXd& w0) const {
  if (h == 0.0) return 0.0;
  const double omega = drive_omega;
  if (!modal) {
    Eigen::MatrixXcd augmented = Eigen::MatrixXcd::Zero(dim + 1, dim + 1);
    augmented.topLeftCorner(dim, dim) = A.cast<Complex>();
    augmented.topLeftCorner(dim, dim).diagonal().array() += Complex(0.0, omega);
    augmented.topRightCorner(dim, 1) = w0.cast<Complex>();
    const Eigen::MatrixXcd E = (augmented * h).exp();
    return (force.cast<Complex>() * E.col(dim).head(dim)).value();
  }
  const Complex i_omega(0.0, omega);
  const Complex E(w0[cosine()], w0[sine()]);
  // Constants (held elongations, slip forces) and the drive's own terms.
  const double constant = force.segment(nz, nh + 1).dot(w0.segment(nz, nh + 1));
  const Complex kappa(force[cosine()], -force[sine()]);
  Complex sum = constant * moment(0, i_omega, h) + 0.5 * kappa * E * moment(0, 2.0 * i_omega, h) + 0.5 * std::conj(kappa) * std::conj(E) * h;
  if (nz > 0) {
    const VectorXcd q0 = V_inverse * w0.head(nz).cast<Complex>();
    const VectorXcd forcing = phi * w0.segment(nz, nh + 1).cast<Complex>();
    for (int j = 0; j < nz; ++j) {
      const Complex l = lambda[j];
      sum += force_V[j] *
             (q0[j] * moment(0, l + i_omega, h) + forcing[j] * phased_response(l, 0.0, omega, h) +
              g_plus[j] * E * phased_response(l, i_omega, omega, h) + g_minus[j] * std::conj(E) * phased_response(l, -i_omega, omega, h));
    }
  }
  return sum;
}

}  // namespace rheo::runtime
