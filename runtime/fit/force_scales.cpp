#include "runtime/fit/force_scales.hpp"

#include "runtime/core/errors.hpp"

#include <algorithm>
#include <cmath>

namespace rheo::runtime {
namespace {

bool close(double a, double b) { return std::abs(a - b) <= 1e-11 * std::max({std::abs(a), std::abs(b), 1e-300}); }

// x0, x1, x2 at p, p + h, p + 2 h: equal steps.
bool affine(double x0, double x1, double x2) {
  return std::abs((x2 - x1) - (x1 - x0)) <= 1e-11 * std::max({std::abs(x0), std::abs(x1), std::abs(x2), 1e-300});
}

bool affine(const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& c) {
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!affine(a[i], b[i], c[i])) return false;
  return true;
}

// Each pair keeps its ratio (a Maxwell element's tau, a friction element's uy).
bool ratios_kept(const std::vector<double>& k0, const std::vector<double>& v0, const std::vector<double>& k1, const std::vector<double>& v1) {
  for (std::size_t i = 0; i < k0.size(); ++i)
    if (!close(v0[i] * k1[i], v1[i] * k0[i])) return false;
  return true;
}

// Every parameter a nested branch reads, by index (model or derived).
std::vector<int> nested_parameters(const Topology& t) {
  std::vector<int> used;
  for (const TreeNode& node : t.nodes)
    for (int p : node.param)
      if (p >= 0) used.push_back(p);
  return used;
}

bool is_scale(const Network& base, int parameter, const std::vector<int>& nested) {
  std::vector<double> values = base.parameters();
  const double p = values[static_cast<std::size_t>(parameter)];
  const double h = 0.25 * std::max(std::abs(p), 1e-3);
  try {
    values[static_cast<std::size_t>(parameter)] = p + h;
    const Network one = base.with_parameters(values);
    values[static_cast<std::size_t>(parameter)] = p + 2.0 * h;
    const Network two = base.with_parameters(values);
    for (int q : nested)
      if (one.parameter(q) != base.parameter(q) || two.parameter(q) != base.parameter(q)) return false;
    const Coefficients &c0 = base.coefficients(), &c1 = one.coefficients(), &c2 = two.coefficients();
    return affine(c0.spring_k, c1.spring_k, c2.spring_k) && affine(c0.dashpot_c, c1.dashpot_c, c2.dashpot_c) &&
           affine(c0.yeoh_d10, c1.yeoh_d10, c2.yeoh_d10) && affine(c0.yeoh_d20, c1.yeoh_d20, c2.yeoh_d20) &&
           affine(c0.yeoh_d30, c1.yeoh_d30, c2.yeoh_d30) && affine(c0.maxwell_k, c1.maxwell_k, c2.maxwell_k) &&
           affine(c0.maxwell_c, c1.maxwell_c, c2.maxwell_c) && affine(c0.friction_k, c1.friction_k, c2.friction_k) &&
           affine(c0.friction_fy, c1.friction_fy, c2.friction_fy) && affine(c0.slider_fy, c1.slider_fy, c2.slider_fy) &&
           ratios_kept(c0.maxwell_k, c0.maxwell_c, c1.maxwell_k, c1.maxwell_c) &&
           ratios_kept(c0.maxwell_k, c0.maxwell_c, c2.maxwell_k, c2.maxwell_c) &&
           ratios_kept(c0.friction_k, c0.friction_fy, c1.friction_k, c1.friction_fy) &&
           ratios_kept(c0.friction_k, c0.friction_fy, c2.friction_k, c2.friction_fy);
  } catch (const UserError&) {  // values the model refuses (a springpot's band): not a scale
    return false;
  }
}

}  // namespace

std::vector<int> force_scales(const Network& network, const std::vector<int>& free) {
  const std::vector<int> nested = nested_parameters(network.topology());
  std::vector<int> scales;
  for (std::size_t j = 0; j < free.size(); ++j)
    if (is_scale(network, free[j], nested)) scales.push_back(static_cast<int>(j));
  return scales;
}

}  // namespace rheo::runtime
