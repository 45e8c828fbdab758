#include "lang/units.hpp"

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>

namespace rheo::lang {
namespace {

struct AtomEntry {
  std::string_view name;
  Unit unit;
};

// Scale = internal value (N, mm, s) per one unit.
constexpr std::array<AtomEntry, 21> kAtoms{{
    {"N", {dim::force, 1.0}},       {"kN", {dim::force, 1e3}},      {"mN", {dim::force, 1e-3}},    {"mm", {dim::length, 1.0}},
    {"m", {dim::length, 1e3}},      {"cm", {dim::length, 10.0}},    {"um", {dim::length, 1e-3}},   {"in", {dim::length, 25.4}},
    {"s", {dim::time, 1.0}},        {"ms", {dim::time, 1e-3}},      {"us", {dim::time, 1e-6}},     {"min", {dim::time, 60.0}},
    {"Hz", {dim::frequency, 1.0}},  {"kHz", {dim::frequency, 1e3}}, {"kg", {dim::mass, 1e-3}},      // 1 kg = 1 N*s^2/m = 1e-3 N*s^2/mm
    {"g", {dim::mass, 1e-6}},       {"rad", {dim::none, 1.0}},      {"Pa", {dim::pressure, 1e-6}},  // 1 Pa = 1 N/m^2 = 1e-6 N/mm^2
    {"kPa", {dim::pressure, 1e-3}}, {"MPa", {dim::pressure, 1.0}},  {"GPa", {dim::pressure, 1e3}},
}};

void append_power(std::string& out, std::string_view base, int power) {
  if (power == 0) return;
  out += base;
  if (power != 1) {  // two appends: "^" + to_string trips GCC 12's -Wrestrict (bug 105651)
    out += '^';
    out += std::to_string(power);
  }
}

}  // namespace

std::optional<Unit> unit_atom(std::string_view name) {
  for (const auto& entry : kAtoms)
    if (entry.name == name) return entry.unit;
  if (name == "deg") return Unit{dim::none, 3.14159265358979323846 / 180.0};
  if (name == "%") return Unit{dim::none, 0.01};
  return std::nullopt;
}

std::string unit_names() {
  std::string out;
  for (const auto& entry : kAtoms) {
    out += entry.name;
    out += ", ";
  }
  return out + "deg, %";
}

std::optional<Unit> parse_unit(std::string_view text) {
  // Angular frequency: the internal frequency unit is Hz (cycles per second), so one radian
  // per second is 1/(2 pi) Hz, not the 1 Hz that rad = 1 would give.
  if (text == "rad/s") return Unit{dim::frequency, 1.0 / (2.0 * 3.14159265358979323846)};
  Unit result{dim::none, 1.0};
  std::size_t i = 0;
  bool divide = false;
  bool first = true;
  while (i < text.size()) {
    if (!first) {
      if (text[i] == '*') divide = false;
      else if (text[i] == '/') divide = true;
      else return std::nullopt;
      ++i;
    }
    std::size_t start = i;
    if (i < text.size() && text[i] == '%') ++i;
    else
      while (i < text.size() && std::isalpha(static_cast<unsigned char>(text[i]))) ++i;
    auto atom = unit_atom(text.substr(start, i - start));
    if (!atom) return std::nullopt;
    int power = 1;
    if (i < text.size() && text[i] == '^') {
      ++i;
      std::size_t pstart = i;
      if (i < text.size() && text[i] == '-') ++i;
      while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) ++i;
      auto [ptr, ec] = std::from_chars(text.data() + pstart, text.data() + i, power);
      if (ec != std::errc{} || ptr != text.data() + i) return std::nullopt;
      if (power < -max_unit_power || power > max_unit_power) return std::nullopt;
    }
    double scale = 1.0;
    for (int p = 0; p < (power < 0 ? -power : power); ++p) scale *= atom->scale;
    if (power < 0) scale = 1.0 / scale;
    Dimension d = atom->dimension.pow(power);
    if (divide) {
      result.dimension = result.dimension / d;
      result.scale /= scale;
    } else {
      result.dimension = result.dimension * d;
      result.scale *= scale;
    }
    const Dimension& r = result.dimension;
    if (std::abs(r.force) > max_unit_power || std::abs(r.length) > max_unit_power || std::abs(r.time) > max_unit_power) return std::nullopt;
    first = false;
  }
  if (first || !std::isfinite(result.scale) || result.scale == 0.0) return std::nullopt;
  return result;
}

std::string ascii_micro_spelling(std::string_view text) {
  std::string out;
  bool micro = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const std::string_view rest = text.substr(i);
    if (rest.starts_with("\xC2\xB5") || rest.starts_with("\xCE\xBC")) {
      out += 'u';
      micro = true;
      ++i;
    } else {
      out += text[i];
    }
  }
  return micro && parse_unit(out) ? out : std::string();
}

std::string internal_unit(const Dimension& d) {
  std::string numerator, denominator;
  auto place = [&](std::string_view base, int power) {
    if (power > 0) {
      if (!numerator.empty()) numerator += "*";
      append_power(numerator, base, power);
    } else if (power < 0) {  // each divisor after its own '/': parse_unit reads left to right
      if (!denominator.empty()) denominator += "/";
      append_power(denominator, base, -power);
    }
  };
  place("N", d.force);
  place("s", d.time > 0 ? d.time : 0);
  place("mm", d.length);
  place("s", d.time < 0 ? d.time : 0);
  if (numerator.empty() && denominator.empty()) return "";
  if (numerator.empty()) numerator.push_back('1');  // not = "1": GCC 12 -Wrestrict (bug 105651)
  return denominator.empty() ? numerator : numerator + "/" + denominator;
}

std::string describe(const Dimension& d) {
  struct Named {
    Dimension dimension;
    std::string_view name;
  };
  static constexpr std::array<Named, 12> kNames{{
      {dim::none, "a plain number"},
      {dim::force, "force"},
      {dim::length, "length"},
      {dim::time, "time"},
      {dim::frequency, "frequency"},
      {dim::velocity, "velocity"},
      {dim::stiffness, "stiffness"},
      {dim::damping, "damping"},
      {dim::mass, "mass"},
      {dim::energy, "energy"},
      {dim::area, "area"},
      {dim::pressure, "modulus"},
  }};
  for (const auto& n : kNames)
    if (n.dimension == d) return d.dimensionless() ? std::string(n.name) : std::string(n.name) + " (" + internal_unit(d) + ")";
  return internal_unit(d);
}

}  // namespace rheo::lang
