#include "runtime/diagnosis/trial.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace rheo::runtime::diagnosis {
namespace {

constexpr double kDecades = 1e3;  // bounds of times, slips, inertances: this factor either side

// A bound to 3 significant digits where that rounds outward (down for LO, up for HI), else to
// the value's 6: rounding is monotone, so a value at its bound still prints within it.
std::string bound(double x, bool upper) {
  const std::string short_form = fmt::format("{:.3g}", x);
  const double read = std::stod(short_form);
  return (upper ? read >= x : read <= x) ? short_form : fmt::format("{:.6g}", x);
}

// `VALUE UNIT in [LO, HI]` with the value in the unit (internal value / per_unit).
std::string bounded(double value, double lo, double hi, double per_unit, const char* unit) {
  return fmt::format("{:.6g} {} in [{}, {}]", value / per_unit, unit, bound(lo / per_unit, false), bound(hi / per_unit, true));
}

std::string around(double value, double per_unit, const char* unit) { return bounded(value, value / kDecades, value * kDecades, per_unit, unit); }

// The free play of a gapped shape: width 2 slip, its centre bias slip within +-U [mm] (the
// largest measured displacement), as the statement inside the shape's series block.
std::string play_statement(const Trial& t, double u) {
  return fmt::format("  gap play (width = {}, center = {})", around(2.0 * t.slip, 1.0, "mm"),
                     bounded(std::clamp(t.bias * t.slip, -u, u), -u, u, 1.0, "mm"));
}

std::string stiffness_argument(double k, const BoundScales& s) {
  return bounded(k, std::min(s.stiffness * 1e-4, k / 10.0), std::max(s.stiffness * 10.0, k * 10.0), 1.0, "N/mm");
}

double inertance(const Trial& t) { return t.stiffness / std::pow(2.0 * std::numbers::pi * t.frequency, 2); }     // N*s^2/mm
double column_damping(const Trial& t) { return 2.0 * t.damping_ratio * std::sqrt(t.stiffness * inertance(t)); }  // N*s/mm

// Lines of the fluid column: spring `chamber` onto `inerter`, `dashpot` and (where t.bulge > 0)
// the walls' spring `bulge` in parallel.
void column_lines(const Trial& t, const BoundScales& s, std::vector<std::string>& lines) {
  lines.push_back(fmt::format("  spring  chamber (k = {})", stiffness_argument(t.stiffness, s)));
  lines.push_back("  parallel column {");
  lines.push_back(fmt::format("    inerter mass    (b = {})", around(inertance(t), 1e-3, "kg")));
  lines.push_back(fmt::format("    dashpot channel (c = {})", around(column_damping(t), 1.0, "N*s/mm")));
  if (t.bulge > 0.0) lines.push_back(fmt::format("    spring  bulge   (k = {})", stiffness_argument(t.bulge, s)));
  lines.push_back("  }");
}

}  // namespace

std::vector<std::string> trial_statement(const Trial& t, const std::string& name, const BoundScales& s) {
  std::vector<std::string> lines;
  const std::string k = stiffness_argument(t.stiffness, s);
  switch (t.shape) {
    case Shape::maxwell: lines.push_back(fmt::format("maxwell {} (k = {}, tau = {})", name, k, around(t.time, 1e-3, "ms"))); break;
    case Shape::friction: lines.push_back(fmt::format("friction {} (k = {}, uy = {})", name, k, around(t.slip, 1e-3, "um"))); break;
    case Shape::capped_maxwell:
      lines.push_back(fmt::format("series {} {{", name));
      lines.push_back(fmt::format("  slider  cap (fy = {})", around(t.stiffness * t.slip, 1.0, "N")));
      lines.push_back(fmt::format("  maxwell arm (k = {}, tau = {})", k, around(t.time, 1e-3, "ms")));
      lines.push_back("}");
      break;
    case Shape::capped_column:
      lines.push_back(fmt::format("series {} {{", name));
      lines.push_back(fmt::format("  slider  cap     (fy = {})", around(t.stiffness * t.slip, 1.0, "N")));
      column_lines(t, s, lines);
      lines.push_back("}");
      break;
    case Shape::tuned_column:
      lines.push_back(fmt::format("series {} {{", name));
      column_lines(t, s, lines);
      lines.push_back("}");
      break;
    case Shape::mass: lines.push_back(fmt::format("inerter {} (b = {})", name, around(inertance(t), 1e-3, "kg"))); break;
    case Shape::asymmetric_friction:
      lines.push_back(fmt::format("friction {} (k = {}, fy_pos = {}, fy_neg = {})", name, k,
                                  around(t.stiffness * t.slip * (1.0 + t.bias), 1.0, "N"), around(t.stiffness * t.slip * (1.0 - t.bias), 1.0, "N")));
      break;
    case Shape::even_spring: {
      const double range = std::max(t.stiffness, s.stiffness) / s.max_displacement;
      const double k2 = std::clamp(t.k2, -0.99 * range, 0.99 * range);
      lines.push_back(fmt::format("poly_spring {} (k1 = {}, k2 = {})", name,
                                  bounded(t.stiffness, t.stiffness / 100.0, t.stiffness * 100.0, 1.0, "N/mm"),
                                  bounded(k2, -range, range, 1.0, "N/mm^2")));
      break;
    }
    case Shape::gapped_spring: {
      const double u = s.max_displacement;
      lines.push_back(fmt::format("series {} {{", name));
      lines.push_back(play_statement(t, u));
      lines.push_back(fmt::format("  spring stop (k = {})", k));
      lines.push_back("}");
      break;
    }
    case Shape::gapped_element: {
      const double u = s.max_displacement;
      lines.push_back(fmt::format("series {} {{", name));
      lines.push_back(play_statement(t, u));
      for (std::size_t at = 0; at <= t.inner.size();) {
        const std::size_t end = std::min(t.inner.find('\n', at), t.inner.size());
        lines.push_back("  " + t.inner.substr(at, end - at));
        at = end + 1;
      }
      lines.push_back("}");
      break;
    }
    case Shape::one_sided_element:
      for (std::size_t at = 0; at <= t.inner.size();) {
        const std::size_t end = std::min(t.inner.find('\n', at), t.inner.size());
        lines.push_back(t.inner.substr(at, end - at));
        at = end + 1;
      }
      break;
    case Shape::yeoh: {
      // D20, D30 ranges relative to the measured stiffness: an added yeoh starts with a small D10.
      const double d10 = t.stiffness / 2.0, range = std::max(d10, s.stiffness / 2.0), u = s.max_displacement;
      const double d20 = std::clamp(t.d20, -0.99 * range / (u * u), 4.99 * range / (u * u));
      const double d30 = std::clamp(t.d30, 0.0, 4.99 * range / std::pow(u, 4));
      lines.push_back(fmt::format("yeoh {} (D10 = {}, D20 = {}, D30 = {})", name, bounded(d10, d10 / 100.0, d10 * 100.0, 1.0, "N/mm"),
                                  bounded(d20, -range / (u * u), 5.0 * range / (u * u), 1.0, "N/mm^3"),
                                  bounded(d30, 0.0, 5.0 * range / std::pow(u, 4), 1.0, "N/mm^5")));
      break;
    }
    case Shape::force_offset: break;  // a data-line setting, not an element (force_offset.hpp)
  }
  return lines;
}

std::string trial_summary(const Trial& t) {
  switch (t.shape) {
    case Shape::maxwell: return fmt::format("a Maxwell element (k = {:.4g} N/mm, tau = {:.4g} ms)", t.stiffness, t.time * 1e3);
    case Shape::friction: return fmt::format("a friction element (k = {:.4g} N/mm, uy = {:.4g} um)", t.stiffness, t.slip * 1e3);
    case Shape::capped_maxwell:
      return fmt::format("a slider (fy = {:.4g} N) in series with a Maxwell element (k = {:.4g} N/mm, tau = {:.4g} ms)", t.stiffness * t.slip,
                         t.stiffness, t.time * 1e3);
    case Shape::capped_column:
      if (t.bulge > 0.0) {  // the column's resonance and damping ratio with the walls' spring beside the chamber: k + k_b
        const double stiffer = std::sqrt(1.0 + t.bulge / t.stiffness);
        return fmt::format(
            "a slider (fy = {:.4g} N) capping a fluid column (k = {:.4g} N/mm, resonance {:.3g} Hz, damping ratio {:.2g}) with bulging "
            "walls (k = {:.4g} N/mm)",
            t.stiffness * t.slip, t.stiffness, t.frequency * stiffer, t.damping_ratio / stiffer, t.bulge);
      }
      return fmt::format("a slider (fy = {:.4g} N) capping a fluid column (k = {:.4g} N/mm, resonance {:.3g} Hz, damping ratio {:.2g})",
                         t.stiffness * t.slip, t.stiffness, t.frequency, t.damping_ratio);
    case Shape::tuned_column:
      return fmt::format("a resonant column (k = {:.4g} N/mm onto an inerter and a dashpot; resonance {:.3g} Hz, damping ratio {:.2g})",
                         t.stiffness, t.frequency, t.damping_ratio);
    case Shape::mass: return fmt::format("a mass (b = {:.4g} kg: -{:.4g} N/mm at {:.3g} Hz)", inertance(t) * 1e3, t.stiffness, t.frequency);
    case Shape::yeoh:
      return t.replaces.empty()
                 ? fmt::format("a yeoh spring (D10 = {:.4g} N/mm, D20 = {:.4g} N/mm^3, D30 = {:.4g} N/mm^5)", t.stiffness / 2, t.d20, t.d30)
                 : fmt::format("a yeoh spring in place of the linear spring '{}' (D10 = {:.4g} N/mm, D20 = {:.4g} N/mm^3, D30 = {:.4g} N/mm^5)",
                               t.replaces, t.stiffness / 2, t.d20, t.d30);
    case Shape::asymmetric_friction:
      return fmt::format("a friction element with one-sided yield forces (k = {:.4g} N/mm, fy_pos = {:.4g} N, fy_neg = {:.4g} N)", t.stiffness,
                         t.stiffness * t.slip * (1.0 + t.bias), t.stiffness * t.slip * (1.0 - t.bias));
    case Shape::even_spring:
      return t.replaces.empty() ? fmt::format("a polynomial spring (k1 = {:.4g} N/mm, k2 = {:.4g} N/mm^2)", t.stiffness, t.k2)
                                : fmt::format("a polynomial spring in place of the linear spring '{}' (k1 = {:.4g} N/mm, k2 = {:.4g} N/mm^2)",
                                              t.replaces, t.stiffness, t.k2);
    case Shape::gapped_spring:
      return fmt::format("a spring (k = {:.4g} N/mm) behind free play (width = {:.4g} mm, center = {:.4g} mm)", t.stiffness, 2.0 * t.slip,
                         t.bias * t.slip);
    case Shape::gapped_element:
      return fmt::format("free play (width = {:.4g} mm, center = {:.4g} mm) in front of '{}'", 2.0 * t.slip, t.bias * t.slip, t.replaces);
    case Shape::one_sided_element:
      return fmt::format("the yield forces of '{}' made one-sided (fy_pos = {:.3g} fy, fy_neg = {:.3g} fy)", t.replaces, 1.0 + t.bias, 1.0 - t.bias);
    case Shape::force_offset:
      return fmt::format("a force offset of {:.4g} N on the measured force{} (force_offset = free on {} data line{})", t.stiffness,
                         t.offsets > 1 ? "s" : "", t.offsets > 1 ? "their" : "its", t.offsets > 1 ? "s" : "");
  }
  return {};
}

int added_parameter_count(const Trial& t) {
  switch (t.shape) {
    case Shape::maxwell:
    case Shape::friction: return 2;
    case Shape::capped_maxwell: return 3;
    case Shape::capped_column: return t.bulge > 0.0 ? 5 : 4;
    case Shape::tuned_column: return 3;
    case Shape::mass: return 1;
    case Shape::yeoh: return t.replaces.empty() ? 3 : 2;
    case Shape::asymmetric_friction: return 3;
    case Shape::even_spring: return t.replaces.empty() ? 2 : 1;
    case Shape::gapped_spring: return 3;
    case Shape::gapped_element: return 2;
    case Shape::one_sided_element: return t.split_parameters;
    case Shape::force_offset: return t.offsets;
  }
  return 0;
}

}  // namespace rheo::runtime::diagnosis
