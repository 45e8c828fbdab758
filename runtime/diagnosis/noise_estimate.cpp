#include "runtime/diagnosis/noise_estimate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

namespace rheo::runtime::diagnosis {
namespace {

using Cell = std::pair<std::size_t, std::size_t>;  // (amplitude level, frequency level)

// Sums of q_i over one axis: their count, sum and sum of squares, and per grid cell the sum and
// count of the q_i it takes part in (as the middle point or a neighbour): its local variance.
struct Moments {
  int m = 0;
  double sum = 0.0, sum_sq = 0.0;
  std::map<Cell, std::pair<double, int>> local;
  void add(double q) { ++m, sum += q, sum_sq += q * q; }
  void add(double q, const std::array<Cell, 3>& cells) {
    add(q);
    for (const Cell& c : cells) local[c].first += q, ++local[c].second;
  }
  double mean() const { return m ? sum / m : 0.0; }
  Moments pooled(const Moments& other) const {
    Moments p{m + other.m, sum + other.sum, sum_sq + other.sum_sq, local};
    for (const auto& [cell, entry] : other.local) p.local[cell].first += entry.first, p.local[cell].second += entry.second;
    return p;
  }
  // The sum over CELLS of their local variances (the mean for a cell in no pseudo-residual):
  // for noise whose size varies over the grid (a damping residual's grows as the phase falls),
  // the edges weigh as much as the middle, as they do in err.
  double total_over(const std::vector<Cell>& cells) const {
    double total = 0.0;
    for (const Cell& c : cells) {
      const auto it = local.find(c);
      total += it == local.end() ? mean() : it->second.first / it->second.second;
    }
    return total;
  }
  // Standard error of the mean: sd(q) sqrt(2/m) (neighbouring q share points).
  double standard_error() const {
    if (m < 2) return 0.0;
    const double variance = std::max(0.0, (sum_sq - sum * sum / m) / (m - 1));
    return std::sqrt(variance * 2.0 / m);
  }
};

// The pseudo-residual's q = e^2/(1 + w_-^2 + w_+^2) of R at X between its neighbours (XL, RL), (XH, RH).
double pseudo_q(double xl, double rl, double x, double r, double xh, double rh) {
  const double wl = (xh - x) / (xh - xl), wh = (x - xl) / (xh - xl);
  const double e = r - (wl * rl + wh * rh);
  return e * e / (1.0 + wl * wl + wh * wh);
}

// The measure of LEVELS (sorted, distinct) that spaces them more evenly: log when they are
// positive and their largest over smallest log step is below that of the linear steps.
std::vector<double> even_measure(const std::vector<double>& levels) {
  if (levels.size() < 3 || levels.front() <= 0.0) return levels;
  auto unevenness = [](const std::vector<double>& x) {
    double lo = 1e300, hi = 0.0;
    for (std::size_t i = 1; i < x.size(); ++i) lo = std::min(lo, x[i] - x[i - 1]), hi = std::max(hi, x[i] - x[i - 1]);
    return hi / lo;
  };
  std::vector<double> logs;
  for (double v : levels) logs.push_back(std::log(v));
  return unevenness(logs) < unevenness(levels) ? logs : levels;
}

struct GridTerm {
  double r_k = 0.0, r_d = 0.0, phase = 0.0;  // phase: model - measured [rad]
};

// Moments of r_K, r_d and the phase along one axis of the grid CELLS (key: (row level, position
// level) -> terms), X the positions' measure; ALONG_FREQUENCY: rows are amplitude levels. With
// the pseudo-residuals of r_K and the phase for the noise profile (PROFILE[0], [1]), at the
// levels AMPLITUDES and FREQUENCIES.
std::array<Moments, 3> along(const std::map<Cell, GridTerm>& cells, const std::vector<double>& x, bool along_frequency,
                             const std::vector<double>& amplitudes, const std::vector<double>& frequencies,
                             std::array<std::vector<ProfileTerm>, 2>& profile) {
  std::array<Moments, 3> out;
  std::map<std::size_t, std::vector<std::pair<std::size_t, GridTerm>>> rows;
  for (const auto& [key, term] : cells) rows[key.first].emplace_back(key.second, term);  // sorted by position
  for (const auto& [row, line] : rows)
    for (std::size_t i = 1; i + 1 < line.size(); ++i) {
      const double xl = x[line[i - 1].first], xi = x[line[i].first], xh = x[line[i + 1].first];
      const GridTerm &l = line[i - 1].second, &c = line[i].second, &h = line[i + 1].second;
      std::array<Cell, 3> at;
      for (std::size_t k = 0; k < 3; ++k) {
        const std::size_t position = line[i + k - 1].first;
        at[k] = along_frequency ? Cell{row, position} : Cell{position, row};
      }
      const double q_k = pseudo_q(xl, l.r_k, xi, c.r_k, xh, h.r_k), q_p = pseudo_q(xl, l.phase, xi, c.phase, xh, h.phase);
      out[0].add(q_k, at);
      out[1].add(pseudo_q(xl, l.r_d, xi, c.r_d, xh, h.r_d), at);
      out[2].add(q_p, at);
      const double wl = (xh - xi) / (xh - xl), wh = (xi - xl) / (xh - xl), norm = 1.0 + wl * wl + wh * wh;
      ProfileTerm term;
      const std::array<Cell, 3> middle_first{at[1], at[0], at[2]};
      const double weights[3]{1.0 / norm, wl * wl / norm, wh * wh / norm};
      for (std::size_t k = 0; k < 3; ++k)
        term.amplitude[k] = amplitudes[middle_first[k].first], term.frequency[k] = frequencies[middle_first[k].second], term.weight[k] = weights[k];
      term.q = q_k, profile[0].push_back(term);
      term.q = q_p, profile[1].push_back(term);
    }
  return out;
}

std::size_t level_index(const std::vector<double>& levels, double value) {
  return static_cast<std::size_t>(std::lower_bound(levels.begin(), levels.end(), value * (1.0 - 1e-9)) - levels.begin());
}

std::vector<double> distinct_levels(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  std::vector<double> out;
  for (double v : values)
    if (out.empty() || std::abs(v - out.back()) > 1e-9 * std::max(std::abs(v), 1e-300)) out.push_back(v);
  return out;
}

void estimate_harmonic(const FitResult& fit, const std::vector<FitDataSet>& data, NoiseEstimate& out) {
  std::vector<double> amplitudes, frequencies;
  int n = 0;
  for (const auto& set : data)
    if (set.is_harmonic()) {
      const HarmonicData& d = set.harmonic();
      amplitudes.insert(amplitudes.end(), d.amplitude.begin(), d.amplitude.end());
      frequencies.insert(frequencies.end(), d.frequency.begin(), d.frequency.end());
      n += static_cast<int>(d.size());
    }
  amplitudes = distinct_levels(amplitudes), frequencies = distinct_levels(frequencies);
  // Cells keyed (amplitude, frequency) and (frequency, amplitude): the first point measured in each.
  std::map<Cell, GridTerm> by_amplitude, by_frequency;
  std::vector<Cell> points;  // the cell of every point measured
  for (std::size_t s = 0; s < data.size(); ++s) {
    if (!data[s].is_harmonic()) continue;
    const HarmonicData& d = data[s].harmonic();
    const DataSetFit& set = fit.datasets[s];
    for (std::size_t j = 0; j < d.size(); ++j) {
      const std::size_t a = level_index(amplitudes, d.amplitude[j]), f = level_index(frequencies, d.frequency[j]);
      const GridTerm term{set.residuals.stiffness[j], set.residuals.damping[j], set.prediction.points[j].measures.phase - d.phase[j]};
      points.emplace_back(a, f);
      by_amplitude.emplace(std::pair{a, f}, term);
      by_frequency.emplace(std::pair{f, a}, term);
    }
  }
  std::array<std::vector<ProfileTerm>, 2> profile_f, profile_a;
  const std::array<Moments, 3> along_f = along(by_amplitude, even_measure(frequencies), true, amplitudes, frequencies, profile_f);
  const std::array<Moments, 3> along_a = along(by_frequency, even_measure(amplitudes), false, amplitudes, frequencies, profile_a);
  // Per term, both axes pooled where they agree within two standard errors of their difference;
  // else the smoother one (the other holds a systematic bend).
  std::array<Moments, 3> taken;
  std::array<bool, 3> along_frequency{}, pooled{};
  for (std::size_t term = 0; term < 3; ++term) {
    const Moments &f = along_f[term], &a = along_a[term];
    if (f.m < kMinPseudoResiduals || a.m < kMinPseudoResiduals) {
      taken[term] = f.m >= a.m ? f : a;
      along_frequency[term] = f.m >= a.m;
    } else if (std::abs(f.mean() - a.mean()) <= 2.0 * std::hypot(f.standard_error(), a.standard_error())) {
      taken[term] = f.pooled(a);
      pooled[term] = true;
    } else {
      taken[term] = f.mean() <= a.mean() ? f : a;
      along_frequency[term] = f.mean() <= a.mean();
    }
  }
  const Moments *k = taken[0].m >= kMinPseudoResiduals ? &taken[0] : nullptr, *dmp = taken[1].m >= kMinPseudoResiduals ? &taken[1] : nullptr,
                *phase = taken[2].m >= kMinPseudoResiduals ? &taken[2] : nullptr;
  if (!k || !dmp || !phase || n == 0) return;
  out.estimated = true;
  out.stiffness = std::sqrt(k->mean());
  out.phase = std::sqrt(phase->mean());
  out.harmonic_along_frequency = along_frequency[0];
  std::vector<std::pair<double, double>> measured;
  for (const Cell& c : points) measured.emplace_back(amplitudes[c.first], frequencies[c.second]);
  // The profile from the pseudo-residuals of the axis taken (term 0: r_K; term 2: the phase).
  auto profile_of = [&](std::size_t term, std::size_t index) {
    std::vector<ProfileTerm> terms = along_frequency[term] || pooled[term] ? profile_f[index] : profile_a[index];
    if (pooled[term]) terms.insert(terms.end(), profile_a[index].begin(), profile_a[index].end());
    return fit_noise_profile(terms, measured);
  };
  out.stiffness_profile = profile_of(0, 0), out.phase_profile = profile_of(2, 1);
  if (out.stiffness_profile.varies) out.stiffness = std::sqrt(out.stiffness_profile.mean_variance);
  if (out.phase_profile.varies) out.phase = std::sqrt(out.phase_profile.mean_variance);
  out.pseudo_residuals = std::min(k->m, dmp->m);
  const double variance = (k->total_over(points) + dmp->total_over(points)) / n;  // per point, of r_K^2 + r_d^2
  out.floor = std::sqrt(n * variance) / n;
  const double se = std::hypot(k->standard_error(), dmp->standard_error());
  out.relative_error = variance > 0.0 ? 0.5 * se / (k->mean() + dmp->mean()) : 0.0;
}

// The noise variance of one history's residual R over times T, allowing the noise to be
// correlated from sample to sample (a rig's anti-aliasing filter): the mean q(h) of the
// pseudo-residuals at lag h (neighbours h samples either side) is, for noise of variance s^2
// with lag-1 autocorrelation rho (AR(1)) plus a residual smooth over the lag (its curvature),
//   q(h) = s^2 (1 - 4/3 rho^h + 1/3 rho^2h) + c h^4,
// (uniform steps: e = r_j - (r_j-h + r_j+h)/2 has variance s^2 (3/2 - 2 rho^h + rho^2h / 2),
// q = e^2 / (3/2)). Independent noise (rho = 0) gives q(h) = s^2 at every lag; correlated noise
// is smoother at short lags and reaches s^2 as rho^h vanishes, so the lag-1 mean alone takes
// rho = 0.5 noise for 0.65 s (0.38 s at rho = 0.8) and calls pure noise a systematic residual.
// Fitted over lags 1..H, H at most 32, an eighth of the samples and a quarter of the drive's
// samples per radian (below), by weighted least squares (each lag
// relative to its q), rho over [0, 0.95] in steps of 0.01, s^2 and c >= 0 solved for each.
struct HistoryNoise {
  double variance = 0.0;        // s^2
  double relative_error = 0.0;  // of s^2: the lag-1 mean's, times q(1)'s share of s^2 taken back
  int pseudo_residuals = 0;     // at lag 1
  bool estimated = false;
};

HistoryNoise history_noise(const std::vector<double>& t, const std::vector<double>& u, const std::vector<double>& r) {
  HistoryNoise out;
  std::vector<double> lags, means;
  Moments first;
  // A miss is a function of the displacement's history, smooth over the lags only where they are
  // short against the time the drive takes to move: at most a quarter of the samples per radian
  // of the drive, RMS(u - mean u) / RMS(u_j+1 - u_j) (N / (2 pi) for a sine of N samples a cycle).
  double mean_u = 0.0, spread = 0.0, steps = 0.0;
  for (double v : u) mean_u += v / static_cast<double>(u.size());
  for (std::size_t j = 0; j < u.size(); ++j) {
    spread += (u[j] - mean_u) * (u[j] - mean_u);
    if (j > 0) steps += (u[j] - u[j - 1]) * (u[j] - u[j - 1]);
  }
  const double per_radian = steps > 0.0 ? std::sqrt(spread / static_cast<double>(u.size()) / (steps / static_cast<double>(u.size() - 1))) : 0.0;
  const auto longest = static_cast<std::size_t>(std::clamp(per_radian / 4.0, 1.0, 32.0));
  for (std::size_t h = 1; h <= longest && 8 * h <= r.size(); h = h < 4 ? h + 1 : h + h / 2) {
    Moments q;
    for (std::size_t j = h; j + h < r.size(); ++j)
      if (t[j + h] > t[j - h]) q.add(pseudo_q(t[j - h], r[j - h], t[j], r[j], t[j + h], r[j + h]));
    if (h == 1) first = q;
    if (q.m < kMinPseudoResiduals) break;
    lags.push_back(static_cast<double>(h)), means.push_back(q.mean());
  }
  if (first.m < kMinPseudoResiduals) return out;
  out.estimated = true;
  out.pseudo_residuals = first.m;
  out.variance = first.mean();
  const double first_se = first.mean() > 0.0 ? first.standard_error() / first.mean() : 0.0;
  out.relative_error = first_se;
  if (lags.size() < 3) return out;
  double best = std::numeric_limits<double>::infinity();
  for (int step = 0; step <= 95; ++step) {
    const double rho = 0.01 * step;
    // Weighted normal equations of q(h) = s2 f(h) + c h^4, weights 1/q(h)^2, s2, c >= 0.
    double aa = 0.0, ab = 0.0, bb = 0.0, ay = 0.0, by = 0.0, yy = 0.0;
    for (std::size_t i = 0; i < lags.size(); ++i) {
      const double w = means[i] > 0.0 ? 1.0 / means[i] : 0.0;
      const double a = w * (1.0 - 4.0 / 3.0 * std::pow(rho, lags[i]) + std::pow(rho, 2.0 * lags[i]) / 3.0), b = w * std::pow(lags[i], 4),
                   y = w * means[i];
      aa += a * a, ab += a * b, bb += b * b, ay += a * y, by += b * y, yy += y * y;
    }
    double s2 = 0.0, c = 0.0;
    if (const double det = aa * bb - ab * ab; det > 1e-12 * aa * bb) s2 = (ay * bb - by * ab) / det, c = (aa * by - ab * ay) / det;
    if (s2 < 0.0 || c < 0.0) {  // one of them at its bound 0: the better of the two one-term fits
      const double s2_alone = aa > 0.0 ? std::max(0.0, ay / aa) : 0.0, c_alone = bb > 0.0 ? std::max(0.0, by / bb) : 0.0;
      const double r_s = yy - 2.0 * s2_alone * ay + s2_alone * s2_alone * aa, r_c = yy - 2.0 * c_alone * by + c_alone * c_alone * bb;
      s2 = r_s <= r_c ? s2_alone : 0.0, c = r_s <= r_c ? 0.0 : c_alone;
    }
    const double residual = yy - 2.0 * (s2 * ay + c * by) + s2 * s2 * aa + 2.0 * s2 * c * ab + c * c * bb;
    if (residual < best) best = residual, out.variance = s2;
  }
  // The lag-1 mean's relative error, scaled as s^2 exceeds it (the longer lags hold fewer independent pseudo-residuals).
  out.relative_error = first_se * std::max(1.0, first.mean() > 0.0 ? out.variance / first.mean() : 1.0);
  return out;
}

void estimate_histories(const FitResult& fit, const std::vector<FitDataSet>& data, NoiseEstimate& out) {
  double variance_sum = 0.0, se_sq = 0.0, lag_sum = 0.0, lag_weight = 0.0;
  int files = 0;
  for (std::size_t s = 0; s < data.size(); ++s) {
    if (data[s].is_harmonic()) continue;
    const HistoryData& h = data[s].history();
    const std::vector<double>& t = h.drive.time;
    const std::vector<double>& model = fit.datasets[s].prediction.force;
    std::vector<double> r(h.force.size());
    for (std::size_t j = 0; j < r.size(); ++j) r[j] = (model[j] - h.force[j]) / h.force_scale;
    const HistoryNoise noise = history_noise(t, h.drive.displacement, r);
    if (!noise.estimated) continue;
    ++files;
    variance_sum += noise.variance;
    se_sq += std::pow(noise.relative_error * noise.variance, 2);
    out.pseudo_residuals += noise.pseudo_residuals;
    double mean = 0.0;
    for (double v : r) mean += v;
    mean /= static_cast<double>(r.size());
    double c0 = 0.0, c1 = 0.0;
    for (std::size_t j = 0; j < r.size(); ++j) {
      c0 += (r[j] - mean) * (r[j] - mean);
      if (j + 1 < r.size()) c1 += (r[j] - mean) * (r[j + 1] - mean);
    }
    if (c0 > 0.0) lag_sum += static_cast<double>(r.size()) * c1 / c0, lag_weight += static_cast<double>(r.size());
  }
  if (files == 0) return;
  out.estimated = true;
  const double variance = variance_sum / files;  // the mean over files of the squared RMS, as the gap takes it
  out.force = std::sqrt(variance);
  out.floor = out.force;
  out.relative_error = variance > 0.0 ? 0.5 * std::sqrt(se_sq) / files / variance : 0.0;
  out.autocorrelation = lag_weight > 0.0 ? lag_sum / lag_weight : 0.0;
}

}  // namespace

NoiseEstimate estimate_noise(const FitResult& fit, const std::vector<FitDataSet>& data) {
  NoiseEstimate out;
  const bool harmonic = std::any_of(data.begin(), data.end(), [](const FitDataSet& set) { return set.is_harmonic(); });
  if (harmonic) estimate_harmonic(fit, data, out);  // the gap is err (6.1) over the harmonic points
  else estimate_histories(fit, data, out);
  return out;
}

double noise_ratio(double gap, const NoiseEstimate& noise, int residual_terms, int parameters) {
  if (!noise.estimated || !(noise.floor > 0.0)) return 0.0;
  const double dof = std::max(1.0, static_cast<double>(residual_terms - parameters)) / std::max(1, residual_terms);
  return gap / (noise.floor * std::sqrt(dof));
}

bool systematic(double gap, const NoiseEstimate& noise, int residual_terms, int parameters) {
  if (!noise.estimated) return false;
  if (!(noise.floor > 0.0)) return gap > 0.0;
  return beyond_noise_ratio(noise_ratio(gap, noise, residual_terms, parameters), noise);
}

bool beyond_noise_ratio(double ratio, const NoiseEstimate& noise) { return ratio > 1.0 + std::max(0.25, 3.0 * noise.relative_error); }


}  // namespace rheo::runtime::diagnosis
