#include "runtime/fit/separable_fit.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/fit/bounded_least_squares.hpp"
#include "runtime/fit/history_scoring.hpp"
#include "runtime/fit/levenberg_marquardt.hpp"

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

 private:
  const AffineResponse& response_;
  const std::vector<FitDataSet>& data_;
  const ScoreSettings& score_;
};

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
  if (all_histories(data)) return solve_history_scales(network, scales, lower, upper, data, score);  // a block of samples at a time
  const AffineResponse response(network, scales, lower, upper, data, score.harmonic);
  const ScaleProblem problem(response, data, score);
  const Eigen::Index n = static_cast<Eigen::Index>(scales.size());
  const Eigen::VectorXd lo = Eigen::Map<const Eigen::VectorXd>(lower.data(), n), hi = Eigen::Map<const Eigen::VectorXd>(upper.data(), n);

  // The least-squares residuals are affine in s: r(s) = r(s0) + A (s - s0), A by unit differences.
  const Eigen::VectorXd s0 = response.start();
  const Eigen::VectorXd r0 = problem.residuals(s0, FitObjective::least_squares);
  Eigen::MatrixXd a(r0.size(), n);
  for (Eigen::Index c = 0; c < n; ++c) {
    Eigen::VectorXd moved = s0;
    const double step = std::max(std::abs(s0(c)), 1e-6);
    const double h = s0(c) + step <= hi(c) ? step : -step;
    moved(c) += h;
    a.col(c) = (problem.residuals(moved, FitObjective::least_squares) - r0) / h;
  }
  if (!a.allFinite() || !r0.allFinite()) throw NumericalError("the residuals of the model's response are not finite; its scales cannot be solved");
  Eigen::VectorXd s = s0 + bounded_least_squares(a, -r0, lo - s0, hi - s0).x;
  s = s.cwiseMax(lo).cwiseMin(hi);
  // The phi objective's residuals are not affine in s: Levenberg-Marquardt from the linear solve.
  if (score.objective != FitObjective::least_squares) {
    LeastSquaresProblem lm;
    lm.residuals = [&](const Eigen::VectorXd& x) { return problem.residuals(x, score.objective); };
    LevenbergMarquardtSettings settings;
    settings.step_tolerance = 1e-9;
    settings.decrease_tolerance = 1e-15;  // the affine response is cheap: stop on the step, not on phi
    // Scales are N/mm, N*s/mm, N: 1e-6 is near zero for each, unless a positive lower bound says
    // the scale lives below that (a master curve's stiffnesses reach 1e-20 N/mm, limits.hpp).
    settings.typical = lo.unaryExpr([](double bound) { return bound > 0.0 ? std::min(bound, 1e-6) : 1e-6; });
    s = levenberg_marquardt(lm, s, lo, hi, settings).x;
  }

  ScaleSolution out;
  out.values = network.parameters();
  for (Eigen::Index j = 0; j < n; ++j) out.values[static_cast<std::size_t>(scales[static_cast<std::size_t>(j)])] = s(j);
  out.objective = problem.residuals(s, score.objective).squaredNorm();
  out.evaluations = static_cast<int>(n) + 1;
  return out;
}

}  // namespace rheo::runtime
