// Physical dimensions and the unit table.
//
// Internal system (the one the runtime computes in): force N, length mm, time s.
// A Dimension is the exponent triple (force, length, time); e.g. stiffness N/mm = (1,-1,0).
// Units at the edges (source files, CSV headers, CLI options, reports) convert to and from
// the internal system with a single scale factor: value_internal = value_in_unit * scale.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace rheo::lang {

struct Dimension {
  int force = 0;
  int length = 0;
  int time = 0;

  friend bool operator==(const Dimension&, const Dimension&) = default;
  Dimension operator*(const Dimension& o) const { return {force + o.force, length + o.length, time + o.time}; }
  Dimension operator/(const Dimension& o) const { return {force - o.force, length - o.length, time - o.time}; }
  Dimension pow(int n) const { return {force * n, length * n, time * n}; }
  bool dimensionless() const { return force == 0 && length == 0 && time == 0; }
};

namespace dim {
inline constexpr Dimension none{0, 0, 0};
inline constexpr Dimension force{1, 0, 0};
inline constexpr Dimension length{0, 1, 0};
inline constexpr Dimension time{0, 0, 1};
inline constexpr Dimension frequency{0, 0, -1};
inline constexpr Dimension velocity{0, 1, -1};
inline constexpr Dimension stiffness{1, -1, 0};
inline constexpr Dimension damping{1, -1, 1};            // N*s/mm
inline constexpr Dimension mass{1, -1, 2};               // N*s^2/mm (= 1000 kg)
inline constexpr Dimension quadratic_damping{1, -2, 2};  // N*s^2/mm^2
inline constexpr Dimension energy{1, 1, 0};              // N*mm
inline constexpr Dimension area{0, 2, 0};                // mm^2
inline constexpr Dimension pressure{1, -2, 0};           // N/mm^2 = MPa: a modulus or a stress
}  // namespace dim

// "stiffness (N/mm)", "length (mm)", or the internal unit for unnamed dimensions ("N/mm^3").
std::string describe(const Dimension& d);
// The internal unit of a dimension, e.g. "N*s/mm", "N/mm^5", "1/s", "" for dimensionless.
std::string internal_unit(const Dimension& d);

struct Unit {
  Dimension dimension;
  double scale = 1.0;  // internal value per unit value
};

// A single unit atom such as "kN", "um", "ms", "Hz", "kg", "deg", "rad", "MPa", "%" (0.01).
// Unknown: nullopt.
std::optional<Unit> unit_atom(std::string_view name);
// Every unit atom, for messages: "N, kN, mN, mm, ..., rad, deg".
std::string unit_names();
// A compound unit such as "N/mm", "N*s/mm", "N/mm^3", "kN/mm", "N s/mm" is not accepted
// (use '*'). Grammar: atom ('^' int)? (('*'|'/') atom ('^' int)?)* . Unknown: nullopt.
// "rad/s" is angular frequency: 1 rad/s = 1/(2 pi) Hz. Also nullopt, whatever the input, when
// an exponent or a dimension of the result exceeds max_unit_power in magnitude, or the scale
// is not a finite non-zero number ("um^-99*us^-99").
inline constexpr int max_unit_power = 99;
std::optional<Unit> parse_unit(std::string_view text);

// A unit written with the micro sign (U+00B5 "µm", or the Greek mu U+03BC "μs"), spelt the
// way rheo reads it: "um", "us", "N*s/um". "" when TEXT has no micro sign, or is no unit with
// each replaced by 'u'. For the hint of an unknown unit.
std::string ascii_micro_spelling(std::string_view text);

}  // namespace rheo::lang
