#include "runtime/fit/levenberg_marquardt.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/fit/damped_step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

namespace rheo::runtime {
namespace {

// Stagnation (levenberg_marquardt.hpp): phi lowered by less than this factor times the
// decrease tolerance over this many iterations.
constexpr std::size_t kStagnationWindow = 5;
constexpr double kStagnationFactor = 100.0;
// A differenced column below this share of the largest column's norm is numerically zero: a
// column that is zero in exact arithmetic differences to rounding, about 1e-16 |r| / h = 1e-10
// |r| at the step of 1e-6 (fit_search.cpp), and 1e-8 leaves that a factor 100. Such a parameter
// is held for that Jacobian's damped steps by a scale kHeldScale times the largest column's.
// (At 1e-6 the specimen-D fit's unidentifiable friction parameters were held too, and its
// two-thread speed-up fell from 1.75 to 1.5, the cause not pinned down.)
constexpr double kInsensitiveColumn = 1e-8;
constexpr double kHeldScale = 1e6;

// r(x), or an empty vector where it is not finite or cannot be evaluated.
Eigen::VectorXd try_residuals(const LeastSquaresProblem& problem, const Eigen::VectorXd& x) {
  try {
    Eigen::VectorXd r = problem.residuals(x);
    return r.allFinite() ? r : Eigen::VectorXd();
  } catch (const NumericalError&) {
    return {};
  }
}

// phi(x) of a problem given by its value (LeastSquaresProblem::value): +inf where it is not
// finite or cannot be evaluated.
double try_value(const LeastSquaresProblem& problem, const Eigen::VectorXd& x) {
  try {
    const double v = problem.value(x);
    return std::isfinite(v) ? v : std::numeric_limits<double>::infinity();
  } catch (const NumericalError&) {
    return std::numeric_limits<double>::infinity();
  }
}

// The reduced Jacobian with STEPS; failing that, once more with each step reversed where the box
// allows (else that column zero, and `complete` false). nullopt where neither can be formed.
std::optional<LeastSquaresProblem::Reduced> reduced_jacobian(const LeastSquaresProblem& problem, const Eigen::VectorXd& x,
                                                             const Eigen::VectorXd& steps, const Eigen::VectorXd& lower,
                                                             const Eigen::VectorXd& upper, bool& complete) {
  const Eigen::Index n = x.size();
  const auto usable = [n](const std::optional<LeastSquaresProblem::Reduced>& r) {
    return r && r->r.rows() == n && r->r.cols() == n && r->c.size() == n;
  };
  std::optional<LeastSquaresProblem::Reduced> reduced = problem.reduced_jacobian(x, steps);
  if (usable(reduced)) return reduced;
  if (!problem.value) return std::nullopt;  // the caller differences the columns from the residuals
  Eigen::VectorXd reversed = -steps;
  for (Eigen::Index c = 0; c < n; ++c)
    if (x(c) + reversed(c) > upper(c) || x(c) + reversed(c) < lower(c)) reversed(c) = 0.0, complete = complete && steps(c) == 0.0;
  reduced = problem.reduced_jacobian(x, reversed);
  return usable(reduced) ? reduced : std::nullopt;
}

// r at each of XS: the problem's batch, or try_residuals on each in turn.
std::vector<Eigen::VectorXd> try_residuals(const LeastSquaresProblem& problem, const std::vector<Eigen::VectorXd>& xs) {
  if (!problem.residuals_batch) {
    std::vector<Eigen::VectorXd> out;
    out.reserve(xs.size());
    for (const Eigen::VectorXd& x : xs) out.push_back(try_residuals(problem, x));
    return out;
  }
  std::vector<Eigen::VectorXd> out = problem.residuals_batch(xs);
  for (Eigen::VectorXd& r : out)
    if (!r.allFinite()) r = Eigen::VectorXd();
  return out;
}

// The forward differences' steps, each into the box: forwards, else backwards, else (a box
// narrower than the step) to the farther bound; 0 for a box of zero width.
Eigen::VectorXd difference_steps(const Eigen::VectorXd& x, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                 const Eigen::VectorXd& typical, double relative_step) {
  Eigen::VectorXd steps(x.size());
  for (Eigen::Index c = 0; c < x.size(); ++c) {
    const double step = relative_step * std::max(std::abs(x(c)), typical(c));
    const double room_up = upper(c) - x(c), room_down = x(c) - lower(c);
    steps(c) = room_up >= step ? step : room_down >= step ? -step : room_up >= room_down ? room_up : -room_down;
  }
  return steps;
}

// Forward differences with the steps above. The moved points are independent: every column's
// first step is evaluated as one batch, then, as a second, the other way for each column whose
// moved point could not be evaluated; where neither can, the column is zero and `complete` is false.
Eigen::MatrixXd difference_jacobian(const LeastSquaresProblem& problem, const Eigen::VectorXd& x, const Eigen::VectorXd& r,
                                    const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, const Eigen::VectorXd& step_sizes, bool& complete) {
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(r.size(), x.size());
  std::vector<double> steps(step_sizes.data(), step_sizes.data() + step_sizes.size());
  std::vector<bool> done(steps.size(), false);
  for (std::size_t c = 0; c < steps.size(); ++c) done[c] = steps[c] == 0.0;  // a box of zero width: the coordinate cannot move
  for (int attempt = 0; attempt < 2; ++attempt) {
    std::vector<Eigen::Index> columns;
    std::vector<double> hs;
    std::vector<Eigen::VectorXd> moved;
    for (Eigen::Index c = 0; c < x.size(); ++c) {
      const auto u = static_cast<std::size_t>(c);
      const double h = attempt == 0 ? steps[u] : -steps[u];
      if (done[u] || x(c) + h > upper(c) || x(c) + h < lower(c)) continue;
      columns.push_back(c);
      hs.push_back(h);
      moved.push_back(x);
      moved.back()(c) += h;
    }
    if (columns.empty()) break;
    const std::vector<Eigen::VectorXd> r_moved = try_residuals(problem, moved);
    for (std::size_t k = 0; k < columns.size(); ++k) {
      const Eigen::Index c = columns[k];
      if (r_moved[k].size() != r.size()) continue;
      j.col(c) = (r_moved[k] - r) / hs[k];
      done[static_cast<std::size_t>(c)] = true;
    }
  }
  complete = std::all_of(done.begin(), done.end(), [](bool d) { return d; });
  return j;
}

}  // namespace

LevenbergMarquardtResult levenberg_marquardt(const LeastSquaresProblem& problem, const Eigen::VectorXd& start, const Eigen::VectorXd& lower,
                                             const Eigen::VectorXd& upper, const LevenbergMarquardtSettings& settings) {
  const Eigen::Index n = start.size();
  const Eigen::VectorXd typical = settings.typical.size() == n ? settings.typical : Eigen::VectorXd::Ones(n);
  LevenbergMarquardtResult out;
  out.x = start.cwiseMax(lower).cwiseMin(upper);
  const bool by_value = static_cast<bool>(problem.value);
  if (by_value && !problem.reduced_jacobian) throw std::logic_error("levenberg_marquardt: a problem given by its value needs reduced_jacobian");
  if (by_value) {
    out.value = try_value(problem, out.x);
    if (!std::isfinite(out.value)) throw NumericalError("the residuals at the start of the least-squares search are not finite");
  } else {
    out.residuals = try_residuals(problem, out.x);
    if (out.residuals.size() == 0) throw NumericalError("the residuals at the start of the least-squares search are not finite");
    out.value = out.residuals.squaredNorm();
  }
  const double floor = 1e-28 * static_cast<double>(by_value ? problem.residual_count : static_cast<std::size_t>(out.residuals.size()));
  double lambda = 1e-3, nu = 2.0;
  out.status = "MAXITER_REACHED";
  std::vector<double> history;  // phi at each Jacobian
  Eigen::VectorXd scale;
  for (out.iterations = 0; out.iterations < settings.max_iterations;) {
    history.push_back(out.value);
    if (history.size() > kStagnationWindow &&
        history[history.size() - 1 - kStagnationWindow] - out.value <= kStagnationFactor * settings.decrease_tolerance * out.value) {
      out.status = "FTOL_REACHED";
      return out;
    }
    if (out.value <= floor) {
      out.status = "STOPVAL_REACHED";
      return out;
    }
    bool complete = true;
    Eigen::MatrixXd j;
    Eigen::VectorXd linear_r = out.residuals;  // r, or c of a reduced Jacobian: the linear model is || j d + linear_r ||^2 + const
    if (problem.jacobian) j = problem.jacobian(out.x, out.residuals);
    if (j.cols() == 0) {
      const Eigen::VectorXd steps = difference_steps(out.x, lower, upper, typical, settings.difference_step);
      std::optional<LeastSquaresProblem::Reduced> reduced;
      if (problem.reduced_jacobian && !problem.jacobian) reduced = reduced_jacobian(problem, out.x, steps, lower, upper, complete);
      if (reduced) j = std::move(reduced->r), linear_r = std::move(reduced->c);
      else if (!by_value) j = difference_jacobian(problem, out.x, out.residuals, lower, upper, steps, complete);
      else {
        out.status = "NO_DESCENT";  // no linear model can be formed here
        return out;
      }
    }
    ++out.iterations;
    if (!j.allFinite()) {
      out.status = "NO_DESCENT";
      return out;
    }
    // Marquardt's scaling, as MINPACK keeps it: the largest column norm seen so far.
    const Eigen::VectorXd norms = j.colwise().norm().transpose().cwiseMax(1e-300);
    scale = scale.size() == norms.size() ? Eigen::VectorXd(scale.cwiseMax(norms)) : norms;
    // First-order test: what the undamped step could still gain, by the linear model (not where
    // a column could not be differenced: it would look insensitive). Only that gain's order
    // against the two tolerances below matters, and its bounded solve is the dearest (with R
    // near singular the step runs into many bounds): || Q^T r ||^2 bounds the gain above, and
    // any damped step within the same box (the first one tried, needed anyway) below, so the
    // undamped step is solved only where neither bound decides.
    // A column numerically zero against the largest (kInsensitiveColumn) carries no information
    // on its parameter: the objective is flat there at the differencing step (a gap's centre
    // where the data see only its width, a shape its element's force does not reach), and its
    // scale, its own column norm, would let the linear model send that parameter across its box
    // on the noise of its gradient (every such trial rejected, the damping driven up until every
    // other step is negligible too). Such parameters are held for this Jacobian's damped steps
    // by a scale kHeldScale times the largest column's: their steps are then below 1e-6 of the
    // residual's size over that column (at the least damping, 1e-12), and within the box.
    Eigen::VectorXd step_scale = scale;
    for (Eigen::Index c = 0; c < n; ++c)
      if (norms(c) <= kInsensitiveColumn * norms.maxCoeff()) step_scale(c) = kHeldScale * norms.maxCoeff();
    const Eigen::VectorXd step_lower = lower - out.x, step_upper = upper - out.x;
    const DampedSteps model(j, linear_r, settings.threads);
    const double tolerance = settings.decrease_tolerance * out.value, near = kStagnationFactor * tolerance;
    std::optional<DampedStep> first;
    double undamped = model.decrease_bound();
    if (undamped > tolerance) {
      if (undamped > near) first = model.step(lambda, step_scale, step_lower, step_upper);
      undamped = first && first->predicted > near ? first->predicted
                                                  : model.step(0.0, scale, step_lower, step_upper, first ? first->d : Eigen::VectorXd()).predicted;
    }
    if (complete && undamped <= tolerance) {
      out.status = "FTOL_REACHED";
      return out;
    }
    // The tests on a step below hold only where the undamped step has little left to gain: a
    // step heavy damping made tiny says nothing about a minimum.
    const bool near_minimum = complete && undamped <= near;
    bool taken = false;
    while (!taken) {
      if (lambda > 1e16) {
        out.status = "NO_DESCENT";
        return out;
      }
      const DampedStep step = first ? *std::exchange(first, std::nullopt) : model.step(lambda, step_scale, step_lower, step_upper);
      const Eigen::VectorXd trial = (out.x + step.d).cwiseMax(lower).cwiseMin(upper);
      const Eigen::VectorXd trial_r = by_value ? Eigen::VectorXd() : try_residuals(problem, trial);
      const double trial_value = by_value                                 ? try_value(problem, trial)
                                 : trial_r.size() == out.residuals.size() ? trial_r.squaredNorm()
                                                                          : std::numeric_limits<double>::infinity();
      if (!(trial_value < out.value)) {
        lambda *= nu;
        nu *= 2.0;
        continue;
      }
      taken = true;
      const double decrease = out.value - trial_value;
      const double rho = step.predicted > 0.0 ? decrease / step.predicted : 1.0;
      lambda *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
      lambda = std::max(lambda, 1e-12);
      nu = 2.0;
      const double moved = ((trial - out.x).cwiseAbs().array() / out.x.cwiseAbs().cwiseMax(typical).array()).maxCoeff();
      out.x = trial, out.residuals = trial_r, out.value = trial_value;
      // MINPACK's test: the step and the model both say phi has stopped falling.
      if (near_minimum && decrease <= settings.decrease_tolerance * out.value && step.predicted <= settings.decrease_tolerance * out.value) {
        out.status = "FTOL_REACHED";
        return out;
      }
      if (decrease <= settings.crawl_tolerance * (out.value + decrease)) {
        out.status = "FTOL_REACHED";
        return out;
      }
      if (near_minimum && moved <= settings.step_tolerance) {
        out.status = "XTOL_REACHED";
        return out;
      }
    }
  }
  return out;
}

}  // namespace rheo::runtime
