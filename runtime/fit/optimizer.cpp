#include "runtime/fit/optimizer.hpp"

#include "runtime/core/errors.hpp"

#include <fmt/format.h>
#include <nlopt.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>

namespace rheo::runtime {
namespace {

struct OptDeleter {
  void operator()(nlopt_opt opt) const { nlopt_destroy(opt); }
};
using OptHandle = std::unique_ptr<std::remove_pointer_t<nlopt_opt>, OptDeleter>;

nlopt_algorithm to_nlopt(Algorithm a) {
  switch (a) {
    case Algorithm::bobyqa: return NLOPT_LN_BOBYQA;
    case Algorithm::sbplx: return NLOPT_LN_SBPLX;
    case Algorithm::neldermead: return NLOPT_LN_NELDERMEAD;
    case Algorithm::direct_l: return NLOPT_GN_DIRECT_L;
    case Algorithm::crs2: return NLOPT_GN_CRS2_LM;
    case Algorithm::isres: return NLOPT_GN_ISRES;
    case Algorithm::mlsl: return NLOPT_G_MLSL_LDS;
  }
  return NLOPT_LN_BOBYQA;
}

OptHandle create(nlopt_algorithm algorithm, unsigned n) {
  OptHandle opt(nlopt_create(algorithm, n));
  if (!opt) throw NumericalError(fmt::format("nlopt_create({}, {}) failed", nlopt_algorithm_name(algorithm), n));
  return opt;
}

void check(nlopt_opt opt, nlopt_result code, const char* call) {
  if (code < 0) {
    const char* detail = opt ? nlopt_get_errmsg(opt) : nullptr;
    throw NumericalError(fmt::format("{} failed: {}{}", call, nlopt_result_to_string(code), detail ? fmt::format(" ({})", detail) : ""));
  }
}

struct Context {
  const Objective* objective;
  std::vector<double> x;
  std::exception_ptr error;
  nlopt_opt opt;
  int evaluations = 0;
  int non_finite = 0;
  double worst_finite = -std::numeric_limits<double>::infinity();

  // What NLopt sees for a non-finite value: worse than anything finite seen so far by a margin,
  // but not so huge that it wrecks the quadratic model of BOBYQA near the point.
  double penalty() const { return std::isfinite(worst_finite) ? worst_finite + 10.0 * std::max(std::abs(worst_finite), 1.0) : 1e300; }
};

double trampoline(unsigned n, const double* x, double* gradient, void* data) noexcept {
  auto* c = static_cast<Context*>(data);
  (void)gradient;  // derivative-free methods only
  try {
    c->x.assign(x, x + n);
    ++c->evaluations;
    const double value = (*c->objective)(c->x);
    if (std::isfinite(value)) {
      c->worst_finite = std::max(c->worst_finite, value);
      return value;
    }
    ++c->non_finite;
    return c->penalty();
  } catch (...) {
    c->error = std::current_exception();
    nlopt_force_stop(c->opt);
    return 1e300;
  }
}

}  // namespace

OptimizationResult minimize(const Objective& objective, std::vector<double> start, const std::vector<double>& lower,
                            const std::vector<double>& upper, const OptimizerSettings& settings) {
  const auto n = static_cast<unsigned>(start.size());
  nlopt_srand(settings.seed);
  OptHandle opt = create(to_nlopt(settings.algorithm), n);
  OptHandle local;
  check(opt.get(), nlopt_set_lower_bounds(opt.get(), lower.data()), "nlopt_set_lower_bounds");
  check(opt.get(), nlopt_set_upper_bounds(opt.get(), upper.data()), "nlopt_set_upper_bounds");
  check(opt.get(), nlopt_set_maxeval(opt.get(), settings.max_evaluations), "nlopt_set_maxeval");
  // Tolerances end local searches; a population method stalls between improvements, so the
  // global ones run on their evaluation budget.
  const bool global = settings.algorithm == Algorithm::direct_l || settings.algorithm == Algorithm::crs2 ||
                      settings.algorithm == Algorithm::isres || settings.algorithm == Algorithm::mlsl;
  if (!global) {
    check(opt.get(), nlopt_set_xtol_rel(opt.get(), settings.relative_x_tolerance), "nlopt_set_xtol_rel");
    check(opt.get(), nlopt_set_ftol_rel(opt.get(), settings.relative_f_tolerance), "nlopt_set_ftol_rel");
  }
  if (settings.algorithm == Algorithm::mlsl) {
    local = create(NLOPT_LN_BOBYQA, n);
    check(local.get(), nlopt_set_xtol_rel(local.get(), settings.relative_x_tolerance), "nlopt_set_xtol_rel (local)");
    check(opt.get(), nlopt_set_local_optimizer(opt.get(), local.get()), "nlopt_set_local_optimizer");
  }
  Context context{&objective, {}, nullptr, opt.get()};
  check(opt.get(), nlopt_set_min_objective(opt.get(), trampoline, &context), "nlopt_set_min_objective");
  for (unsigned i = 0; i < n; ++i) start[i] = std::clamp(start[i], lower[i], upper[i]);
  double value = 0.0;
  const nlopt_result code = nlopt_optimize(opt.get(), start.data(), &value);
  if (context.error) std::rethrow_exception(context.error);
  if (code != NLOPT_ROUNDOFF_LIMITED && code != NLOPT_MAXEVAL_REACHED) check(opt.get(), code, "nlopt_optimize");
  return {start, value, context.evaluations, context.non_finite, nlopt_result_to_string(code)};
}

}  // namespace rheo::runtime
