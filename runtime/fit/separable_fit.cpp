#include "runtime/fit/separable_fit.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/fit/bounded_least_squares.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rheo::runtime {
namespace {

// The affine quantities of all files' predictions, in file order: (K'_1, K''_1) per harmonic
// point [N/mm], F per history sample [N].
Eigen::VectorXd flatten(const std::vector<Prediction>& predictions) {
  std::vector<double> q;
  for (const Prediction& p : predictions) {
    for (const HarmonicPoint& point : p.points) {
      q.push_back(point.measures.storage);
      q.push_back(point.measures.loss);
    }
    q.insert(q.end(), p.force.begin(), p.force.end());
  }
  return Eigen::Map<const Eigen::VectorXd>(q.data(), static_cast<Eigen::Index>(q.size()));
}

// The predictions whose affine quantities are q, shaped like `like` (same points and samples).
std::vector<Prediction> unflatten(const Eigen::VectorXd& q, const std::vector<Prediction>& like, HarmonicDefinition definition) {
  std::vector<Prediction> out = like;
  Eigen::Index at = 0;
  for (Prediction& p : out) {
    for (HarmonicPoint& point : p.points) {
      const double storage = q(at++), loss = q(at++);
      const double u0 = point.amplitude;
      point.measures = measures_from(u0 * std::hypot(storage, loss), storage, loss, u0, definition);
    }
    for (double& f : p.force) f = q(at++);
  }
  return out;
}

// The model's response as an affine function of the scales.
class AffineResponse {
 public:
  AffineResponse(const Network& network, const std::vector<int>& scales, const std::vector<double>& lower, const std::vector<double>& upper,
                 const std::vector<FitDataSet>& data, const HarmonicOptions& harmonic)
      : data_(data), s0_(static_cast<Eigen::Index>(scales.size())) {
    std::vector<double> values = network.parameters();
    for (std::size_t j = 0; j < scales.size(); ++j) {
      double& s = values[static_cast<std::size_t>(scales[j])];
      s = std::clamp(s, lower[j], upper[j]);
      s0_(static_cast<Eigen::Index>(j)) = s;
    }
    shape_ = predict_all(network.with_parameters(values), harmonic);
    base_ = flatten(shape_);
    basis_.resize(base_.size(), s0_.size());
    for (std::size_t j = 0; j < scales.size(); ++j) {
      double& s = values[static_cast<std::size_t>(scales[j])];
      // Half the value (the sign kept: a Maxwell element's k > 0) or a thousandth of the range.
      const double step = std::max(0.5 * std::abs(s), 1e-3 * (std::isfinite(upper[j] - lower[j]) ? upper[j] - lower[j] : 1.0));
      const double h = s + step <= upper[j] ? step : -step;
      s += h;
      basis_.col(static_cast<Eigen::Index>(j)) = (flatten(predict_all(network.with_parameters(values), harmonic)) - base_) / h;
      s = s0_(static_cast<Eigen::Index>(j));
    }
    if (!base_.allFinite() || !basis_.allFinite())
      throw NumericalError("the model's response at these parameters is not finite (NaN or infinite force); its scales cannot be solved");
  }

  Eigen::VectorXd quantities(const Eigen::VectorXd& s) const { return base_ + basis_ * (s - s0_); }
  const std::vector<Prediction>& shape() const { return shape_; }
  const Eigen::VectorXd& start() const { return s0_; }

 private:
  std::vector<Prediction> predict_all(const Network& network, const HarmonicOptions& harmonic) const {
    std::vector<Prediction> p;
    for (const FitDataSet& set : data_) p.push_back(predict(network, set, FitMethod::exact, harmonic, nullptr));
    return p;
  }

  const std::vector<FitDataSet>& data_;
  std::vector<Prediction> shape_;
  Eigen::VectorXd s0_, base_;
  Eigen::MatrixXd basis_;
};

class ScaleProblem {
 public:
  ScaleProblem(const AffineResponse& response, const std::vector<FitDataSet>& data, const ScoreSettings& score)
      : response_(response), data_(data), score_(score) {}

  Eigen::VectorXd residuals(const Eigen::VectorXd& s, FitObjective objective) const {
    ScoreSettings score = score_;
    score.objective = objective;
    const std::vector<Prediction> p = unflatten(response_.quantities(s), response_.shape(), score_.harmonic.definition);
    std::vector<double> r;
    for (std::size_t f = 0; f < data_.size(); ++f) append_residuals(data_[f], p[f], score, r);
    return Eigen::Map<const Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size()));
  }

  // Forward differences of the residuals at s, stepping into the box.
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& s, const Eigen::VectorXd& r, FitObjective objective, const Eigen::VectorXd& upper,
                           double relative_step) const {
    Eigen::MatrixXd j(r.size(), s.size());
    for (Eigen::Index c = 0; c < s.size(); ++c) {
      Eigen::VectorXd moved = s;
      const double step = relative_step * std::max(std::abs(s(c)), 1e-6);
      const double h = s(c) + step <= upper(c) ? step : -step;
      moved(c) += h;
      j.col(c) = (residuals(moved, objective) - r) / h;
    }
    return j;
  }

 private:
  const AffineResponse& response_;
  const std::vector<FitDataSet>& data_;
  const ScoreSettings& score_;
};

// Levenberg-Marquardt with bounded steps (Marquardt's diagonal scaling) from s.
Eigen::VectorXd levenberg_marquardt(const ScaleProblem& problem, Eigen::VectorXd s, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                    FitObjective objective) {
  Eigen::VectorXd r = problem.residuals(s, objective);
  double value = r.squaredNorm();
  // Residuals at rounding level (relative 1e-14 each): nothing left to fit.
  const double floor = 1e-28 * static_cast<double>(r.size());
  if (value <= floor) return s;
  double lambda = 1e-3;
  for (int iteration = 0; iteration < 200 && std::isfinite(value); ++iteration) {
    const Eigen::MatrixXd j = problem.jacobian(s, r, objective, upper, 1e-7);
    if (!j.allFinite()) break;
    const Eigen::VectorXd scale = j.colwise().norm().transpose().cwiseMax(1e-300);
    const Eigen::Index m = j.rows(), n = j.cols();
    bool improved = false;
    while (!improved && lambda < 1e16) {
      Eigen::MatrixXd a(m + n, n);
      a.topRows(m) = j;
      a.bottomRows(n) = (std::sqrt(lambda) * scale).asDiagonal();
      Eigen::VectorXd b = Eigen::VectorXd::Zero(m + n);
      b.head(m) = -r;
      const Eigen::VectorXd step = bounded_least_squares(a, b, lower - s, upper - s).x;
      const Eigen::VectorXd trial = (s + step).cwiseMax(lower).cwiseMin(upper);
      const Eigen::VectorXd trial_r = problem.residuals(trial, objective);
      const double trial_value = trial_r.squaredNorm();
      if (std::isfinite(trial_value) && trial_value < value) {
        improved = true;
        const double decrease = value - trial_value;
        const double moved = ((trial - s).array() / s.cwiseAbs().cwiseMax(1e-300).array()).abs().maxCoeff();
        s = trial, r = trial_r, value = trial_value;
        if (moved <= 1e-9) return s;
        lambda = std::max(lambda * 0.3, 1e-12);
        if (decrease <= 1e-10 * value || value <= floor) return s;
      } else {
        lambda *= 4.0;
      }
    }
    if (!improved) break;
  }
  return s;
}

}  // namespace

bool predictions_affine(const Network& network, const std::vector<FitDataSet>& data, const ScoreSettings& score) {
  if (score.method != FitMethod::exact) return false;
  for (const FitDataSet& set : data)
    if (set.is_harmonic() && score.harmonic.definition != HarmonicDefinition::first_harmonic && !network.topology().is_linear) return false;
  return true;
}

ScaleSolution solve_scales(const Network& network, const std::vector<int>& scales, const std::vector<double>& lower,
                           const std::vector<double>& upper, const std::vector<FitDataSet>& data, const ScoreSettings& score) {
  if (scales.size() != lower.size() || scales.size() != upper.size())
    throw std::logic_error("solve_scales: one lower and one upper bound per scale");
  const AffineResponse response(network, scales, lower, upper, data, score.harmonic);
  const ScaleProblem problem(response, data, score);
  const Eigen::Index n = static_cast<Eigen::Index>(scales.size());
  const Eigen::VectorXd lo = Eigen::Map<const Eigen::VectorXd>(lower.data(), n), hi = Eigen::Map<const Eigen::VectorXd>(upper.data(), n);

  // The least-squares residuals are affine in s: r(s) = r(s0) + A (s - s0), A by unit differences.
  const Eigen::VectorXd s0 = response.start();
  const Eigen::VectorXd r0 = problem.residuals(s0, FitObjective::least_squares);
  const Eigen::MatrixXd a = problem.jacobian(s0, r0, FitObjective::least_squares, hi, 1.0);
  if (!a.allFinite() || !r0.allFinite()) throw NumericalError("the residuals of the model's response are not finite; its scales cannot be solved");
  Eigen::VectorXd s = s0 + bounded_least_squares(a, -r0, lo - s0, hi - s0).x;
  s = s.cwiseMax(lo).cwiseMin(hi);
  s = levenberg_marquardt(problem, s, lo, hi, score.objective);

  ScaleSolution out;
  out.values = network.parameters();
  for (Eigen::Index j = 0; j < n; ++j) out.values[static_cast<std::size_t>(scales[static_cast<std::size_t>(j)])] = s(j);
  out.objective = problem.residuals(s, score.objective).squaredNorm();
  out.evaluations = static_cast<int>(n) + 1;
  return out;
}

}  // namespace rheo::runtime
