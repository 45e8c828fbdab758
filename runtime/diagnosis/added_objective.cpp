#include "runtime/diagnosis/added_objective.hpp"

#include <algorithm>
#include <cmath>

namespace rheo::runtime::diagnosis {

using Complex = std::complex<double>;

AddedObjective::AddedObjective(const FitResult& fit, const std::vector<FitDataSet>& data, const ScoreSettings& score) : data_(data), score_(score) {
  for (const auto& set : fit.datasets) {
    scratch_.push_back(set.prediction);
    base_force_.push_back(set.prediction.force);
    std::vector<Complex> k;
    for (const auto& point : set.prediction.points) k.push_back(std::polar(point.measures.stiffness, point.measures.phase));
    base_k_.push_back(std::move(k));
  }
  for (const FitDataSet& set : data) {
    harmonic_terms_.emplace_back();
    if (set.is_harmonic()) harmonic_terms_.back().emplace(set, score);
  }
}

double AddedObjective::operator()(const std::vector<const Signature*>& basis, const std::vector<double>& coefficient) const {
  double sum = 0.0;
  for (std::size_t f = 0; f < data_.size(); ++f) {
    const FitDataSet& set = data_[f];
    Prediction& p = scratch_[f];
    if (set.is_harmonic()) {
      sum += harmonic_objective(f, basis, coefficient);
      continue;
    }
    std::copy(base_force_[f].begin(), base_force_[f].end(), p.force.begin());
    add_history(set, basis, coefficient, f, p.force);
    residuals_.clear();
    append_residuals(set, p, score_, residuals_);
    for (double r : residuals_) sum += r * r;
  }
  return sum;
}

// Harmonic set F: beta by Gauss-Newton from 0, two steps each kept only where it lowers the
// objective: exact in one for the least-squares objective (its residuals are affine in beta),
// close for phi (eq. 5.38).
double AddedObjective::harmonic_objective(std::size_t f, const std::vector<const Signature*>& basis, const std::vector<double>& coefficient) const {
  const std::size_t points = base_k_[f].size();
  trial_k_.resize(points);
  double scale = 0.0;
  for (std::size_t j = 0; j < points; ++j) {
    Complex k = base_k_[f][j];
    for (std::size_t b = 0; b < basis.size(); ++b) k += coefficient[b] * basis[b]->harmonic[f][j];
    trial_k_[j] = k;
    scale = std::max(scale, std::abs(k));
  }
  // The terms append_residuals gives for stiffness |K*| and phase arg K*, without the angle.
  const ComplexResiduals& terms = *harmonic_terms_[f];
  auto residuals_at = [&](double beta, std::vector<double>& out) { return terms.terms(trial_k_, beta, out); };
  double beta = 0.0, best = residuals_at(0.0, residuals_);
  const double h = 1e-6 * std::max(scale, 1e-300);
  for (int step = 0; step < 2 && std::isfinite(best); ++step) {
    residuals_at(beta + h, moved_);
    double jr = 0.0, jj = 0.0;
    for (std::size_t i = 0; i < moved_.size(); ++i) {
      const double d = (moved_[i] - residuals_[i]) / h;
      jr += d * residuals_[i], jj += d * d;
    }
    if (!(jj > 0.0)) break;
    const double next = beta - jr / jj;
    const double value = residuals_at(next, moved_);
    if (!(value < best)) break;
    beta = next, best = value;
    residuals_.swap(moved_);
  }
  return best;
}

// F_m + sum a s, then beta u + dc with beta the least-squares refit of the linear stiffness
// and, for a free force offset (fit/force_offset.hpp), dc that of the offset, jointly:
//   [u.u  sum u] [beta]   [u.r  ]
//   [sum u   M ] [dc  ] = [sum r],  r = F_exp - F (M samples; dc = 0 for a declared offset).
void AddedObjective::add_history(const FitDataSet& set, const std::vector<const Signature*>& basis, const std::vector<double>& coefficient,
                                 std::size_t f, std::vector<double>& force) {
  const HistoryData& h = set.history();
  const std::vector<double>& u = h.drive.displacement;
  double uu = 0.0, ur = 0.0, su = 0.0, sr = 0.0;
  for (std::size_t j = 0; j < force.size(); ++j) {
    for (std::size_t b = 0; b < basis.size(); ++b) force[j] += coefficient[b] * basis[b]->history[f][j];
    uu += u[j] * u[j];
    ur += u[j] * (h.force[j] - force[j]);
    su += u[j];
    sr += h.force[j] - force[j];
  }
  double beta = uu > 0.0 ? ur / uu : 0.0, dc = 0.0;
  const auto m = static_cast<double>(force.size());
  if (const double det = uu * m - su * su; set.force_offset.free && det > 1e-12 * uu * m) {
    beta = (ur * m - su * sr) / det;
    dc = (uu * sr - su * ur) / det;
  } else if (set.force_offset.free) {
    dc = sr / m;  // u is constant: the offset takes it all
    beta = 0.0;
  }
  for (std::size_t j = 0; j < force.size(); ++j) force[j] += beta * u[j] + dc;
}

}  // namespace rheo::runtime::diagnosis
