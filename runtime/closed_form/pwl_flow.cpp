// The exact flow of a mode of a piecewise-linear branch (pwl_mode.hpp): modal closed forms,
// or the matrix exponential where the state block is defective.
#include "runtime/closed_form/pwl_mode.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <unsupported/Eigen/MatrixFunctions>

#include <array>
#include <cmath>

namespace rheo::runtime {
namespace {

using Eigen::MatrixXd;
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

// M_0(z, h) = (e^{zh} - 1)/z with no cancellation for small |zh|: e^{x + iy} - 1 =
// expm1(x) cos y - 2 sin^2(y/2) + i e^x sin y; h at z = 0.
Complex first_moment(Complex z, double h) {
  if (z == 0.0) return h;
  const double x = z.real() * h, y = z.imag() * h, half_sine = std::sin(0.5 * y);
  const Complex numerator(std::expm1(x) * std::cos(y) - 2.0 * half_sine * half_sine, std::exp(x) * std::sin(y));
  return numerator / z;
}

// a b as the library forms it, (ac - bd, ad + bc), without its recovery of infinities from
// NaN products (the operands are finite here): the same bits, a few instructions fewer.
[[gnu::always_inline]] inline Complex times(Complex a, Complex b) {
  return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()};
}

// e^z without the special-value handling of std::exp(complex) (z is finite here).
[[gnu::always_inline]] inline Complex exponential(Complex z) {
  const double magnitude = std::exp(z.real());
  if (z.imag() == 0.0) return {magnitude, 0.0};
  return {magnitude * std::cos(z.imag()), magnitude * std::sin(z.imag())};
}

// P(lambda, mu, tau) = int_0^tau e^{lambda (tau - s)} e^{mu s} ds = (e^{mu tau} - e^{lambda tau})/(mu - lambda),
// tau e^{lambda tau} at mu = lambda; from e^{lambda tau}, e^{mu tau}, d = mu - lambda and 1/d.
[[gnu::always_inline]] inline Complex response(Complex e_lambda, Complex e_mu, Complex d, Complex inverse_d, double tau) {
  if (std::norm(d) * tau * tau >= 1e-6) return times(e_mu - e_lambda, inverse_d);
  const Complex dt = d * tau;
  return e_lambda * tau * (1.0 + dt * (0.5 + dt * (1.0 / 6.0 + dt * (1.0 / 24.0 + dt / 120.0))));
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

// The eigendecomposition of A_zz into STRUCTURE (modal false where it fails, the
// eigenvectors' reciprocal condition is below 1e-8, or V diag(lambda) V^-1 misses A_zz by more
// than 1e-11 of its largest entry).
void decompose_state_block(const PwlMatrix& A, int nz, PwlModeStructure& structure) {
  structure.modal = false;
  if (nz == 0) {
    structure.V.resize(0, 0), structure.V_inverse.resize(0, 0), structure.lambda.resize(0);
    structure.modal = true;
    return;
  }
  const MatrixXd Azz = A.topLeftCorner(nz, nz);
  Eigen::EigenSolver<MatrixXd> eig(Azz);
  if (eig.info() != Eigen::Success) return;
  Eigen::FullPivLU<Eigen::MatrixXcd> lu(eig.eigenvectors());
  if (!(lu.rcond() > 1e-8)) return;
  structure.V = eig.eigenvectors();
  structure.lambda = eig.eigenvalues();
  structure.V_inverse = lu.inverse();
  // The solver gives a complex pair's eigenvalues and eigenvectors exactly conjugate, the
  // first with the positive imaginary part; V^-1's rows for them are conjugate to rounding,
  // and made so exactly (PwlModalWeights).
  for (int j = 0; j < nz; ++j) {
    const std::complex<double> l = structure.lambda[j];
    const bool pair = j + 1 < nz && l.imag() > 0.0 && structure.lambda[j + 1] == std::conj(l);
    structure.weight[static_cast<std::size_t>(j)] = pair ? 2 : 1;
    if (!pair) continue;
    structure.V_inverse.row(j + 1) = structure.V_inverse.row(j).conjugate();
    structure.weight[static_cast<std::size_t>(++j)] = 0;
  }
  const double error = (structure.V * structure.lambda.asDiagonal() * structure.V_inverse - Azz.cast<Complex>()).cwiseAbs().maxCoeff();
  structure.modal = error <= 1e-11 * std::max(Azz.cwiseAbs().maxCoeff(), 1e-300);
}

}  // namespace

void PwlModeSystem::decompose(PwlModeStructure& structure) {
  modal = false;
  if (!structure.filled) decompose_state_block(A, nz, structure);
  if (!structure.modal) return;
  V = structure.V, V_inverse = structure.V_inverse, lambda = structure.lambda, weight = structure.weight;
  // phi and force_V involve no drive column (the same at every frequency): formed by the build
  // that fills the structure and kept there.
  if (!structure.filled) {
    // Complex temporaries are cleared on construction (9 kB each): the product is formed from
    // this thread's copy of the real block, without one.
    thread_local PwlComplexMatrix held;
    held = A.block(0, nz, nz, nh + 1).cast<Complex>();
    structure.phi.noalias() = V_inverse * held;
    structure.force_V = force.head(nz).cast<Complex>() * V;
  }
  phi = structure.phi, force_V = structure.force_V;
  const PwlComplexVector a_c = A.col(cosine()).head(nz).cast<Complex>(), a_s = A.col(sine()).head(nz).cast<Complex>();
  g_plus = 0.5 * (V_inverse * (a_c - Complex(0.0, 1.0) * a_s));
  g_minus = 0.5 * (V_inverse * (a_c + Complex(0.0, 1.0) * a_s));
  auto reciprocal = [](Complex d) { return d == 0.0 ? Complex(0.0) : 1.0 / d; };
  gap_zero.resize(nz), gap_plus.resize(nz), gap_minus.resize(nz);
  for (int j = 0; j < nz; ++j) {
    gap_zero[j] = reciprocal(-lambda[j]);
    gap_plus[j] = reciprocal(Complex(0.0, drive_omega) - lambda[j]);
    gap_minus[j] = reciprocal(Complex(0.0, -drive_omega) - lambda[j]);
  }
  modal = true;
}

namespace {

// The modal factors of a flow over tau: e^{lambda tau} and P(lambda, mu, tau) for mu = 0, i w,
// -i w (the last two times g+-), one exponential per mode and one sine and cosine in all.
struct ModalFactors {
  PwlComplexVector decay, constant, plus, minus;
  double cos_step = 1.0, sin_step = 0.0;
};

// Without DRIVE only decay and constant (plus, minus, cos_step and sin_step left as they were).
void modal_factors(const PwlModeSystem& s, double tau, ModalFactors& f, bool drive = true) {
  const Complex i_omega(0.0, s.drive_omega);
  if (drive) f.cos_step = std::cos(s.drive_omega * tau), f.sin_step = std::sin(s.drive_omega * tau);
  const Complex e_plus(f.cos_step, f.sin_step), e_minus = std::conj(e_plus);
  f.decay.resize(s.nz), f.constant.resize(s.nz), f.plus.resize(s.nz), f.minus.resize(s.nz);
  Complex to_plus{0.0, 0.0}, to_minus{0.0, 0.0};  // mode j's responses to the drive, before g+-
  for (int j = 0; j < s.nz; ++j) {
    const Complex l = s.lambda[j];
    if (j > 0 && l.imag() != 0.0 && l == std::conj(s.lambda[j - 1])) {
      // The second of a conjugate pair (the eigensolver gives them exactly conjugate, and so
      // are gap_zero and gap_plus/gap_minus swapped): every factor is the conjugate of the
      // first's, to the last bit, without another exponential.
      f.decay[j] = std::conj(f.decay[j - 1]);
      f.constant[j] = std::conj(f.constant[j - 1]);
      if (!drive) continue;
      const Complex plus = std::conj(to_minus), minus = std::conj(to_plus);
      f.plus[j] = times(s.g_plus[j], plus);
      f.minus[j] = times(s.g_minus[j], minus);
      to_plus = plus, to_minus = minus;
      continue;
    }
    const Complex e = exponential(l * tau);
    f.decay[j] = e;
    f.constant[j] = response(e, 1.0, -l, s.gap_zero[j], tau);
    if (!drive) continue;
    to_plus = response(e, e_plus, i_omega - l, s.gap_plus[j], tau);
    to_minus = response(e, e_minus, -i_omega - l, s.gap_minus[j], tau);
    f.plus[j] = times(s.g_plus[j], to_plus);
    f.minus[j] = times(s.g_minus[j], to_minus);
  }
}

}  // namespace

PwlVector PwlModeSystem::advance(double tau, const PwlVector& w) const {
  if (tau == 0.0) return w;
  if (!modal) return (A * tau).exp() * w;
  // Scratch of this thread: complex storage is cleared on construction, which would cost more
  // than the flow itself.
  thread_local ModalFactors f;
  thread_local PwlComplexVector q;
  modal_factors(*this, tau, f);
  PwlVector out = w;
  const double s0 = w[sine()], c0 = w[cosine()];
  const Complex E(c0, s0);
  q.resize(nz);
  for (int j = 0; j < nz; ++j) {
    if (weight[static_cast<std::size_t>(j)] == 0) continue;  // the conjugate of q_{j-1}
    Complex free{0.0, 0.0}, held{0.0, 0.0};
    for (int k = 0; k < nz; ++k) free += V_inverse(j, k) * w[k];
    for (int k = 0; k <= nh; ++k) held += phi(j, k) * w[nz + k];
    q[j] = times(f.decay[j], free) + times(f.constant[j], held) + times(E, f.plus[j]) + times(std::conj(E), f.minus[j]);
  }
  for (int i = 0; i < nz; ++i) {
    double sum = 0.0;
    for (int j = 0; j < nz; ++j) {
      const double weight_j = weight[static_cast<std::size_t>(j)];
      if (weight_j != 0.0) sum += weight_j * (V(i, j).real() * q[j].real() - V(i, j).imag() * q[j].imag());
    }
    out[i] = sum;
  }
  out[sine()] = s0 * f.cos_step + c0 * f.sin_step;
  out[cosine()] = c0 * f.cos_step - s0 * f.sin_step;
  return out;
}

namespace {

// The Taylor sum w + sum_{k=1..terms} (delta A)^k w / k! of PwlModeSystem::nudge (OUT may be W),
// for a state of D entries at compile time: the products unrolled, in registers.
template <int D>
void taylor_fixed(const PwlMatrix& A, double delta, int terms, const PwlVector& w, PwlVector& out) {
  using Vector = Eigen::Matrix<double, D, 1>;
  const Eigen::Map<const Eigen::Matrix<double, D, D>> a(A.data());  // A is D x D, stored contiguously
  Vector term = w.template head<D>(), sum = term;
  for (int k = 1; k <= terms; ++k) {
    const Vector next = a.lazyProduct(term);
    term = next * (delta / k);
    sum += term;
  }
  out = sum;
}

void taylor_dynamic(const PwlMatrix& A, double delta, int terms, const PwlVector& w, PwlVector& out) {
  thread_local PwlVector term, next;
  out = w, term = w;
  for (int k = 1; k <= terms; ++k) {
    next.noalias() = A.lazyProduct(term);
    term = next * (delta / k);
    out += term;
  }
}

}  // namespace

bool PwlModeSystem::nudge(double delta, const PwlVector& w, PwlVector& out) const {
  const double x1 = reach * std::abs(delta), x2 = reach_squared * std::abs(delta);
  if (!(x2 <= 0.05)) return false;
  // Terms k = 1..K: ||A^k|| |delta|^k <= x2^(k-1) max(x1, x2) (||A^2m|| <= ||A^2||^m).
  int terms = 0;
  for (double bound = (x1 + x2) / (1.0 - x2); terms < 16 && bound > 1e-17; ++terms) bound *= x2 / (terms + 2.0);
  if (terms == 16) return false;
  // The small states of the usual branches (a slider-capped column: 5 and 6 entries) at sizes
  // known to the compiler.
  switch (dim) {
    case 4: taylor_fixed<4>(A, delta, terms, w, out); break;
    case 5: taylor_fixed<5>(A, delta, terms, w, out); break;
    case 6: taylor_fixed<6>(A, delta, terms, w, out); break;
    case 7: taylor_fixed<7>(A, delta, terms, w, out); break;
    case 8: taylor_fixed<8>(A, delta, terms, w, out); break;
    default: taylor_dynamic(A, delta, terms, w, out); break;
  }
  return true;
}

PwlMatrix PwlModeSystem::propagator(double tau) const {
  if (!modal) return (A * tau).exp();
  thread_local ModalFactors f;  // as in advance()
  modal_factors(*this, tau, f);
  PwlMatrix P = PwlMatrix::Identity(dim, dim);
  // Column k of the z rows: Re V diag(factor) (row k of the modal map), for the free block
  // (V^-1), the held block (phi) and the drive (E = i for the sine column, 1 for the cosine).
  const Complex i(0.0, 1.0);
  for (int r = 0; r < nz; ++r) {
    for (int k = 0; k < nz; ++k) {
      Complex sum{0.0, 0.0};
      for (int j = 0; j < nz; ++j) sum += V(r, j) * f.decay[j] * V_inverse(j, k);
      P(r, k) = sum.real();
    }
    for (int k = 0; k <= nh; ++k) {
      Complex sum{0.0, 0.0};
      for (int j = 0; j < nz; ++j) sum += V(r, j) * f.constant[j] * phi(j, k);
      P(r, nz + k) = sum.real();
    }
    Complex sine{0.0, 0.0}, cosine{0.0, 0.0};
    for (int j = 0; j < nz; ++j) sine += V(r, j) * (i * (f.plus[j] - f.minus[j])), cosine += V(r, j) * (f.plus[j] + f.minus[j]);
    P(r, this->sine()) = sine.real();
    P(r, this->cosine()) = cosine.real();
  }
  P(sine(), sine()) = f.cos_step, P(sine(), cosine()) = f.sin_step;
  P(cosine(), sine()) = -f.sin_step, P(cosine(), cosine()) = f.cos_step;
  return P;
}

void PwlModeSystem::propagate(double tau, PwlMatrix& S) const {
  if (tau == 0.0) return;
  const Eigen::Index columns = S.cols();
  if (!modal) {
    const PwlMatrix P = (A * tau).exp(), before = S;
    S.noalias() = P * before;
    return;
  }
  thread_local ModalFactors f;  // as in advance()
  modal_factors(*this, tau, f, false);
  std::array<Complex, kPwlMaxDim> q;
  for (Eigen::Index c = 0; c < columns; ++c) {
    double* column = S.col(c).data();
    for (int j = 0; j < nz; ++j) {
      if (weight[static_cast<std::size_t>(j)] == 0) continue;  // the conjugate of q_{j-1}
      Complex free{0.0, 0.0}, held{0.0, 0.0};
      for (int k = 0; k < nz; ++k) free += V_inverse(j, k) * column[k];
      for (int k = 0; k < nh; ++k) held += phi(j, k) * column[nz + k];
      q[static_cast<std::size_t>(j)] = times(f.decay[j], free) + times(f.constant[j], held);
    }
    for (int r = 0; r < nz; ++r) {
      double sum = 0.0;
      for (int j = 0; j < nz; ++j) {
        const double weight_j = weight[static_cast<std::size_t>(j)];
        const Complex qj = q[static_cast<std::size_t>(j)];
        if (weight_j != 0.0) sum += weight_j * (V(r, j).real() * qj.real() - V(r, j).imag() * qj.imag());
      }
      column[r] = sum;
    }
  }
}

Complex PwlModeSystem::phased_force_integral(double h, const PwlVector& w0) const {
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
  // int_0^h e^{mu tau} e^{i w tau} dtau for the drive's mu = 0, i w, -i w, shared by every mode.
  const Complex at_zero = first_moment(i_omega, h), at_plus = first_moment(2.0 * i_omega, h);
  const double at_minus = h;
  // Constants (held elongations, slip forces) and the drive's own terms.
  const double constant = force.segment(nz, nh + 1).dot(w0.segment(nz, nh + 1));
  const Complex kappa(force[cosine()], -force[sine()]);
  Complex sum = constant * at_zero + times(times(0.5 * kappa, E), at_plus) + times(0.5 * std::conj(kappa), std::conj(E)) * at_minus;
  // Mode j: q_j(0) e^{lambda tau} and the responses P(lambda, mu, tau) to the constant forcing
  // and the drive; int P e^{i w tau} = (M_0(mu + i w) - M_0(lambda + i w))/(mu - lambda) away
  // from mu = lambda, by its series near it.
  for (int j = 0; j < nz; ++j) {
    Complex free{0.0, 0.0}, held{0.0, 0.0};
    for (int k = 0; k < nz; ++k) free += V_inverse(j, k) * w0[k];
    for (int k = 0; k <= nh; ++k) held += phi(j, k) * w0[nz + k];
    const Complex l = lambda[j], own = first_moment(l + i_omega, h);
    auto phased = [&](Complex mu, Complex shared, Complex gap) {
      const Complex d = mu - l;
      return std::norm(d) * h * h >= 1e-6 ? times(shared - own, gap) : phased_response(l, mu, omega, h);
    };
    sum += times(force_V[j], times(free, own) + times(held, phased(0.0, at_zero, gap_zero[j])) +
                                 times(times(g_plus[j], E), phased(i_omega, at_plus, gap_plus[j])) +
                                 times(times(g_minus[j], std::conj(E)), phased(-i_omega, at_minus, gap_minus[j])));
  }
  return sum;
}

}  // namespace rheo::runtime
