#include "runtime/io/column_roles.hpp"

#include "lang/text_encoding.hpp"
#include "lang/units.hpp"
#include "runtime/core/errors.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <stdexcept>

namespace rheo::runtime {
namespace {

struct RoleSpec {
  Role role;
  std::string_view name;
  std::vector<std::string_view> usual;  // column_key() form, in order of preference
  lang::Dimension dimension;            // in the component's terms
  bool material;                        // may be given as a modulus (stiffness) or a strain (length)
  const char* kind;                     // for messages
  const char* example;                  // a unit of that kind
};

const std::vector<RoleSpec>& specs() {
  using namespace lang;
  static const std::vector<RoleSpec> table{
      {Role::time, "time", {"time", "t", "test time", "elapsed time"}, dim::time, false, "time (s)", "s"},
      {Role::displacement,
       "displacement",
       {"displacement", "position", "stroke", "travel", "deflection", "disp", "x", "u"},
       dim::length,
       false,
       "length (mm)",
       "mm"},
      {Role::force, "force", {"force", "load", "standard force", "reaction force", "f"}, dim::force, false, "force (N)", "N"},
      {Role::amplitude,
       "amplitude",
       {"amplitude", "displacement amplitude", "dynamic amplitude", "strain amplitude", "oscillation strain", "dynamic strain", "strain"},
       dim::length,
       true,
       "length (mm), or a strain (%, -, mm/mm) with the specimen's height",
       "mm"},
      {Role::frequency,
       "frequency",
       {"frequency", "freq", "angular frequency", "circular frequency", "omega"},
       dim::frequency,
       false,
       "frequency (1/s)",
       "Hz"},
      {Role::stiffness,
       "stiffness",
       {"stiffness", "dynamic stiffness", "complex stiffness", "|k*|", "k*", "kdyn", "k dyn", "complex modulus", "dynamic modulus", "|e*|", "e*",
        "|g*|", "g*"},
       dim::stiffness,
       true,
       "stiffness (N/mm), or a modulus (Pa, MPa, N/mm^2) with the specimen's area and height",
       "N/mm"},
      {Role::phase,
       "phase",
       {"phase", "phase angle", "loss angle", "delta", "phase shift"},
       dim::none,
       false,
       "none (a plain number, or deg for a phase)",
       "deg"},
      {Role::storage,
       "storage",
       {"storage", "storage modulus", "storage stiffness", "k'", "e'", "g'", "k stor", "e stor", "g stor"},
       dim::stiffness,
       true,
       "stiffness (N/mm), or a modulus (Pa, MPa, N/mm^2) with the specimen's area and height",
       "N/mm"},
      {Role::loss,
       "loss",
       {"loss", "loss modulus", "loss stiffness", "k''", "e''", "g''", "k\"", "e\"", "g\"", "k loss", "e loss", "g loss"},
       dim::stiffness,
       true,
       "stiffness (N/mm), or a modulus (Pa, MPa, N/mm^2) with the specimen's area and height",
       "N/mm"},
      {Role::weight, "weight", {"weight"}, dim::none, false, "none (a plain number)", "-"},
      {Role::preload,
       "preload",
       {"preload", "mean displacement", "static displacement", "static preload", "mean strain", "static strain", "preload strain"},
       dim::length,
       true,
       "length (mm), or a strain (%, -, mm/mm) with the specimen's height",
       "mm"},
  };
  return table;
}

const RoleSpec& spec_of(Role role) {
  for (const auto& s : specs())
    if (s.role == role) return s;
  throw std::logic_error("column_roles: a role without a spec");
}

// The material form of a role's dimension: a modulus for a stiffness, a strain for a length.
lang::Dimension material_dimension(const RoleSpec& s) { return s.dimension == lang::dim::stiffness ? lang::dim::pressure : lang::dim::none; }

// A strain is a plain number written as one: %, -, mm/mm; not an angle (rad, deg).
bool strain_unit(const std::string& unit) {
  const std::string key = column_key(unit);
  return key != "rad" && key != "deg" && key != "°" && !key.empty();
}

bool is_material_unit(const Table& t, int c, const RoleSpec& s) {
  const auto& unit = t.parsed[static_cast<std::size_t>(c)];
  if (!s.material || !unit || unit->dimension != material_dimension(s)) return false;
  return s.dimension != lang::dim::length || strain_unit(t.units[static_cast<std::size_t>(c)]);
}

[[noreturn]] void fail_at_unit(const Table& t, int c, const std::string& message) {
  const auto i = static_cast<std::size_t>(c);
  throw DataError(fmt::format("{}:{}:{}: error: {}", t.path, t.units_row > 0 ? t.units_row : t.header_row, t.unit_columns[i], message));
}

std::string unit_advice(const Table& t, const std::string& name, const char* example) {
  return t.units_row > 0 ? fmt::format("write its unit in the units row, e.g. '{}'", example)
                         : fmt::format("write it as 'name [unit]', e.g. '{} [{}]'", lang::printable(name), example);
}

}  // namespace

std::string_view role_name(Role role) { return spec_of(role).name; }

std::optional<Role> role_named(std::string_view name) {
  for (const auto& s : specs())
    if (s.name == name) return s.role;
  return std::nullopt;
}

lang::Dimension role_dimension(Role role) { return spec_of(role).dimension; }
const char* role_unit_kind(Role role) { return spec_of(role).kind; }
const char* role_unit_example(Role role) { return spec_of(role).example; }
std::string role_usual_names(Role role) {
  std::string out;
  for (const auto& name : spec_of(role).usual) out += (out.empty() ? "" : ", ") + std::string(name);
  return out;
}

ColumnReading column_reading(const std::vector<lang::ColumnName>& columns) {
  ColumnReading reading;
  for (const auto& named : columns) {
    const auto role = role_named(named.role);
    if (!role) throw std::logic_error("column_reading: the checker passed an unknown column role '" + named.role + "'");
    reading.columns.emplace_back(*role, named.name);
  }
  return reading;
}

bool role_suits(const Table& t, int c, Role role) {
  const RoleSpec& s = spec_of(role);
  const auto i = static_cast<std::size_t>(c);
  if (t.units[i].empty()) return role == Role::weight;
  const auto& unit = t.parsed[i];
  if (!unit) return false;
  return unit->dimension == s.dimension || is_material_unit(t, c, s);
}

int find_role(const Table& t, Role role, const ColumnReading& reading) {
  for (const auto& [named_role, name] : reading.columns) {
    if (named_role != role) continue;
    const int c = t.column(name);
    if (c < 0)
      throw DataError(fmt::format("{}the data line reads '{}' from a column '{}', which this table does not have; name one of its columns ({})",
                                  header_error(t), role_name(role), lang::printable(name), header_columns(t)));
    return c;
  }
  int first = -1;
  for (const auto usual : spec_of(role).usual) {
    for (std::size_t i = 0; i < t.names.size(); ++i) {
      if (column_key(t.names[i]) != usual) continue;
      bool claimed = false;  // a column the data line names for another role is that role's
      for (const auto& named : reading.columns) claimed = claimed || column_key(named.second) == usual;
      if (claimed) continue;
      if (role_suits(t, static_cast<int>(i), role)) return static_cast<int>(i);
      if (first < 0) first = static_cast<int>(i);
    }
  }
  return first;
}

bool is_material(const Table& t, int c) {
  for (const auto& s : specs())
    if (is_material_unit(t, c, s)) return true;
  return false;
}

std::vector<double> role_values(const Table& t, int c, Role role, const ColumnReading& reading) {
  const RoleSpec& s = spec_of(role);
  const auto i = static_cast<std::size_t>(c);
  const std::string& name = t.names[i];
  const std::string& unit = t.units[i];
  if (!t.problems[i].empty()) throw DataError(t.problems[i]);
  if (unit.empty() && role != Role::weight)
    fail_at_unit(t, c, fmt::format("column '{}' has no unit; {}", lang::printable(name), unit_advice(t, name, s.example)));
  if (!unit.empty() && !t.parsed[i])
    fail_at_unit(t, c,
                 fmt::format("unknown unit '{}' in column '{}'; use units such as s, ms, mm, um, m, N, kN, N/mm, Hz, rad/s, deg, %, MPa",
                             lang::printable(unit), lang::printable(name)));
  if (!role_suits(t, c, role)) {
    const lang::Dimension d = t.parsed[i]->dimension;
    fail_at_unit(t, c,
                 fmt::format("column '{}' has unit '{}', {}; {} needs a unit of {}, e.g. '{} [{}]'", lang::printable(name), lang::printable(unit),
                             d.dimensionless() ? std::string("a plain number") : "a " + lang::describe(d), s.name, s.kind, s.name, s.example));
  }
  std::vector<double> values = t.columns[i];
  if (is_material_unit(t, c, s)) {
    const bool modulus = s.dimension == lang::dim::stiffness;
    if (!reading.height || (modulus && !reading.area))
      fail_at_unit(t, c,
                   fmt::format("column '{}' is a {} ({}); give the specimen's geometry on the data line ({}) so that rheo can turn it into {}",
                               lang::printable(name), modulus ? "modulus" : "strain", lang::printable(unit),
                               modulus ? "area = 314 mm^2, height = 10 mm" : "height = 10 mm",
                               modulus ? "stiffness (K = E A / h)" : "displacement (u = strain h)"));
    const double factor = modulus ? *reading.area / *reading.height : *reading.height;
    for (double& v : values) v *= factor;
  }
  return values;
}

std::vector<double> need_role(const Table& t, Role role, const ColumnReading& reading, const std::string& what, const std::string& hint) {
  const int c = find_role(t, role, reading);
  if (c < 0)
    throw DataError(fmt::format("{}{} need a column '{}'{}; add it, or name the column that holds it on the data line (columns = \"{} = ...\") ({})",
                                header_error(t), what, role_name(role), hint, role_name(role), header_columns(t)));
  return role_values(t, c, role, reading);
}

}  // namespace rheo::runtime
