#include "runtime/closed_form/closed_form_sensitivity.hpp"

#include "runtime/closed_form/periodic_closed_form.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rheo::runtime {

std::vector<double> coefficient_vector(const Coefficients& c) {
  std::vector<double> v{c.spring_k, c.dashpot_c};
  for (std::size_t i = 0; i < c.yeoh_d10.size(); ++i) v.insert(v.end(), {c.yeoh_d10[i], c.yeoh_d20[i], c.yeoh_d30[i]});
  for (std::size_t i = 0; i < c.maxwell_k.size(); ++i) v.insert(v.end(), {c.maxwell_k[i], c.maxwell_c[i]});
  for (std::size_t i = 0; i < c.friction_k.size(); ++i) v.insert(v.end(), {c.friction_k[i], c.friction_fy[i]});
  v.insert(v.end(), c.slider_fy.begin(), c.slider_fy.end());
  return v;
}

bool has_coefficient_sensitivities(const Network& network) { return network.topology().subtrees.empty(); }

HarmonicSensitivity harmonic_sensitivity(const Network& network, double amplitude, double frequency, HarmonicDefinition definition) {
  if (!has_coefficient_sensitivities(network)) throw std::logic_error("harmonic_sensitivity: the network has subtrees");
  double peak = 0.0;
  const std::optional<HarmonicPoint> point = try_closed_form_harmonic_point(network, amplitude, frequency, definition, 0.0, &peak);
  if (!point || !std::isfinite(peak)) throw std::logic_error("harmonic_sensitivity: no half-wave symmetric closed form");
  const Coefficients& c = network.coefficients();
  const double pi = std::numbers::pi;
  const double u0 = amplitude, omega = 2.0 * pi * frequency;
  const double s = std::sin(peak), cs = std::cos(peak), u = u0 * s;

  HarmonicSensitivity out;
  out.point = *point;
  auto add = [&](double force_amplitude, double storage, double loss) {
    out.force_amplitude.push_back(force_amplitude);
    out.storage.push_back(storage);
    out.loss.push_back(loss);
  };
  add(u, 1.0, 0.0);                  // spring k
  add(omega * u0 * cs, 0.0, omega);  // dashpot c
  for (std::size_t i = 0; i < c.yeoh_d10.size(); ++i) {
    add(2.0 * u, 2.0, 0.0);
    add(4.0 * u * u * u, 3.0 * u0 * u0, 0.0);
    add(6.0 * u * u * u * u * u, 3.75 * u0 * u0 * u0 * u0, 0.0);
  }
  for (std::size_t i = 0; i < c.maxwell_k.size(); ++i) {
    const double x = omega * c.maxwell_c[i] / c.maxwell_k[i], x2 = x * x, q = 1.0 / ((1.0 + x2) * (1.0 + x2));
    const double storage_k = x2 * (x2 - 1.0) * q, loss_k = 2.0 * x2 * x * q;
    const double storage_c = 2.0 * omega * x * q, loss_c = omega * (1.0 - x2) * q;
    add(u0 * (storage_k * s + loss_k * cs), storage_k, loss_k);
    add(u0 * (storage_c * s + loss_c * cs), storage_c, loss_c);
  }
  for (std::size_t i = 0; i < c.friction_k.size(); ++i) {
    const double k = c.friction_k[i], fy = c.friction_fy[i], uy = fy / k;
    if (u0 <= uy) {  // elastic throughout: a spring k
      add(u, 1.0, 0.0);
      add(0.0, 0.0, 0.0);
      continue;
    }
    const double sigma = 2.0 * uy / u0 - 1.0, root = std::sqrt(std::max(0.0, 1.0 - sigma * sigma));
    const double g = std::asin(sigma) + 0.5 * pi + sigma * root, g_prime = 2.0 * root;
    const bool slipping = peak >= std::asin(sigma);
    add(slipping ? 0.0 : u0 * (1.0 + s), g / pi - (k / pi) * g_prime * 2.0 * fy / (k * k * u0), 4.0 * fy * fy / (pi * k * k * u0 * u0));
    add(slipping ? 1.0 : -1.0, 2.0 * g_prime / (pi * u0), 4.0 * (u0 - 2.0 * uy) / (pi * u0 * u0));
  }
  for (std::size_t i = 0; i < c.slider_fy.size(); ++i) add(1.0, 0.0, 4.0 / (pi * u0));

  return out;
}

MeasureDerivative measure_derivative(const HarmonicSensitivity& s, HarmonicDefinition definition, double d_force_amplitude, double d_storage,
                                     double d_loss) {
  const CycleMeasures& m = s.point.measures;
  const double u0 = s.point.amplitude;
  MeasureDerivative d;
  if (definition == HarmonicDefinition::thesis) {
    d.stiffness = d_force_amplitude / u0;
    if (m.damping_clamped || !(m.force_amplitude > 0.0)) return d;  // sin = 1, cos = 0 held
    const double d_damping = (u0 * d_loss - m.damping * d_force_amplitude) / m.force_amplitude;
    d.sine = d_damping;
    const double cosine = std::cos(m.phase);
    if (cosine != 0.0) d.cosine = -m.damping * d_damping / cosine;
    return d;
  }
  const double k = m.stiffness;  // |K*_1|, with K'_1 = m.storage and K''_1 = m.loss
  if (!(k > 0.0)) return d;
  d.stiffness = (m.storage * d_storage + m.loss * d_loss) / k;
  d.sine = d_loss / k - m.loss * d.stiffness / (k * k);
  d.cosine = d_storage / k - m.storage * d.stiffness / (k * k);
  return d;
}

}  // namespace rheo::runtime
