#include "runtime/diagnosis/noise_profile.hpp"

#include <array>
#include <cmath>
#include <cstddef>

namespace rheo::runtime::diagnosis {
namespace {

using Vec = std::array<double, 3>;
using Mat = std::array<Vec, 3>;

// A x = b by Gaussian elimination with partial pivoting; false where A is singular.
bool solve(Mat a, Vec b, Vec& x) {
  for (std::size_t c = 0; c < 3; ++c) {
    std::size_t pivot = c;
    for (std::size_t r = c + 1; r < 3; ++r)
      if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
    if (!(std::abs(a[pivot][c]) > 1e-300)) return false;
    std::swap(a[c], a[pivot]), std::swap(b[c], b[pivot]);
    for (std::size_t r = c + 1; r < 3; ++r) {
      const double m = a[r][c] / a[c][c];
      for (std::size_t k = c; k < 3; ++k) a[r][k] -= m * a[c][k];
      b[r] -= m * b[c];
    }
  }
  for (std::size_t c = 3; c-- > 0;) {
    double s = b[c];
    for (std::size_t k = c + 1; k < 3; ++k) s -= a[c][k] * x[k];
    x[c] = s / a[c][c];
  }
  return true;
}

struct Design {
  double log_a = 0.0, log_f = 0.0;
  Vec at(double a, double f) const { return {1.0, std::log(a) - log_a, std::log(f) - log_f}; }
};

// -2 ln L of THETA over TERMS (noise_profile.hpp), with its gradient and Fisher information.
double deviance(const std::vector<ProfileTerm>& terms, const Design& design, const Vec& theta, Vec* gradient, Mat* fisher) {
  double total = 0.0;
  if (gradient) *gradient = {};
  if (fisher) *fisher = {};
  for (const ProfileTerm& t : terms) {
    double mu = 0.0;
    Vec dmu{};
    for (std::size_t k = 0; k < 3; ++k) {
      if (t.weight[k] == 0.0) continue;
      const Vec x = design.at(t.amplitude[k], t.frequency[k]);
      const double v = std::exp(theta[0] * x[0] + theta[1] * x[1] + theta[2] * x[2]);
      mu += t.weight[k] * v;
      for (std::size_t i = 0; i < 3; ++i) dmu[i] += t.weight[k] * v * x[i];
    }
    if (!(mu > 0.0)) return INFINITY;
    total += std::log(mu) + t.q / mu;
    if (gradient)
      for (std::size_t i = 0; i < 3; ++i) (*gradient)[i] += (mu - t.q) / (mu * mu) * dmu[i];
    if (fisher)
      for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j) (*fisher)[i][j] += dmu[i] * dmu[j] / (mu * mu);
  }
  return total;
}

}  // namespace

double NoiseProfile::factor(double amplitude, double frequency) const {
  if (!varies) return 1.0;
  return scale * std::exp(amplitude_slope * (std::log(amplitude) - log_a) + frequency_slope * (std::log(frequency) - log_f));
}

NoiseProfile fit_noise_profile(const std::vector<ProfileTerm>& terms, const std::vector<std::pair<double, double>>& points) {
  NoiseProfile out;
  if (terms.size() < 6 || points.empty()) return out;
  Design design;
  for (const auto& [a, f] : points) design.log_a += std::log(a), design.log_f += std::log(f);
  design.log_a /= static_cast<double>(points.size()), design.log_f /= static_cast<double>(points.size());
  double mean_q = 0.0;
  for (const ProfileTerm& t : terms) mean_q += t.q;
  mean_q /= static_cast<double>(terms.size());
  if (!(mean_q > 0.0)) return out;
  // One size: v = mean q (every mu_j = v, the weights summing to 1).
  const double one_size = static_cast<double>(terms.size()) * (std::log(mean_q) + 1.0);
  Vec theta{std::log(mean_q), 0.0, 0.0};
  double current = deviance(terms, design, theta, nullptr, nullptr);
  for (int iteration = 0; iteration < 50; ++iteration) {
    Vec g{}, step{};
    Mat f{};
    deviance(terms, design, theta, &g, &f);
    if (!solve(f, g, step)) return out;
    double length = 1.0, next = INFINITY;
    Vec trial{};
    for (int halving = 0; halving < 30; ++halving, length *= 0.5) {
      for (std::size_t i = 0; i < 3; ++i) trial[i] = theta[i] - length * step[i];
      next = deviance(terms, design, trial, nullptr, nullptr);
      if (next <= current) break;
    }
    if (!(next <= current)) break;
    const double gain = current - next;
    theta = trial, current = next;
    if (gain < 1e-9 * (1.0 + std::abs(current))) break;
  }
  out.deviance = one_size - current;
  if (!(out.deviance > kProfileTest)) return out;
  out.varies = true;
  out.amplitude_slope = theta[1], out.frequency_slope = theta[2];
  out.log_a = design.log_a, out.log_f = design.log_f;
  double mean = 0.0;
  for (const auto& [a, f] : points) mean += std::exp(theta[1] * (std::log(a) - design.log_a) + theta[2] * (std::log(f) - design.log_f));
  out.scale = static_cast<double>(points.size()) / mean;
  out.mean_variance = std::exp(theta[0]) / out.scale;
  return out;
}

}  // namespace rheo::runtime::diagnosis
