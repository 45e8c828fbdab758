#include "runtime/io/harmonic_data.hpp"

#include "lang/limits.hpp"
#include "lang/text_encoding.hpp"
#include "runtime/core/errors.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <numbers>
#include <utility>

namespace rheo::runtime {

HarmonicData harmonic_data_from_table(const Table& t) { return harmonic_data_from_table(t, DataReading{}); }

HarmonicData harmonic_data_from_table(const Table& t, const DataReading& reading) {
  const ColumnReading& how = reading.columns;
  const std::string what = "harmonic data";
  HarmonicData d;
  d.path = t.path;
  const int amplitude_column = find_role(t, Role::amplitude, how);
  if (amplitude_column >= 0 && (reading.amplitude || reading.strain_amplitude))
    throw DataError(fmt::format("{}the data line gives an amplitude, and the table has an amplitude column '{}'; remove one of them ({})",
                                header_error(t), lang::printable(t.names[static_cast<std::size_t>(amplitude_column)]), header_columns(t)));
  if (amplitude_column < 0 && reading.amplitude) {
    d.amplitude.assign(t.rows.size(), *reading.amplitude);
  } else if (amplitude_column < 0 && reading.strain_amplitude) {
    if (!how.height)
      throw DataError(
          fmt::format("{}the data line gives the amplitude as a strain; give the specimen's height too (height = 10 mm) so that "
                      "rheo can turn it into displacement",
                      header_error(t)));
    d.amplitude.assign(t.rows.size(), *reading.strain_amplitude * *how.height);
  } else {
    d.amplitude = need_role(t, Role::amplitude, how, what, " [mm] (or an amplitude on the data line: amplitude = 0.1 mm)");
  }
  d.frequency = need_role(t, Role::frequency, how, what, " [Hz]");
  const int stiffness = find_role(t, Role::stiffness, how), phase = find_role(t, Role::phase, how);
  const int storage = find_role(t, Role::storage, how), loss = find_role(t, Role::loss, how);
  const bool polar = stiffness >= 0 && phase >= 0 && role_suits(t, stiffness, Role::stiffness) && role_suits(t, phase, Role::phase);
  const bool cartesian = storage >= 0 && loss >= 0 && role_suits(t, storage, Role::storage) && role_suits(t, loss, Role::loss);
  if (polar || (!cartesian && (stiffness >= 0 || storage < 0))) {
    d.stiffness = need_role(t, Role::stiffness, how, what, " [N/mm] (or storage and loss columns)");
    d.phase = need_role(t, Role::phase, how, what, " [deg]");
    d.stiffness_column = stiffness;
    d.phase_column = phase;
  } else {
    const auto storage_values = need_role(t, Role::storage, how, what, " [N/mm]");
    const auto loss_values = need_role(t, Role::loss, how, what, " [N/mm] next to storage");
    for (std::size_t i = 0; i < storage_values.size(); ++i) {
      d.stiffness.push_back(std::hypot(storage_values[i], loss_values[i]));
      d.phase.push_back(std::atan2(loss_values[i], storage_values[i]));
    }
    d.stiffness_column = storage;
    d.phase_column = loss;
  }
  d.amplitude_column = amplitude_column;
  d.frequency_column = find_role(t, Role::frequency, how);
  d.material = is_material(t, d.stiffness_column) || (amplitude_column >= 0 && is_material(t, amplitude_column));
  d.rows = t.rows;
  const int weight_column = find_role(t, Role::weight, how);
  d.weight = weight_column >= 0 ? role_values(t, weight_column, Role::weight, how) : std::vector<double>(d.size(), 1.0);
  std::map<std::pair<double, double>, int> seen;
  for (std::size_t i = 0; i < d.size(); ++i) {
    auto fail = [&](int column, const std::string& message) {
      if (column < 0) throw DataError(fmt::format("{}:{}:1: error: {}", t.path, t.rows[i], message));
      throw DataError(fmt::format("{}:{}:{}: error: {} (column '{}')", t.path, t.rows[i], t.cell_column(i, column), message,
                                  lang::printable(t.names[static_cast<std::size_t>(column)])));
    };
    if (!(d.weight[i] >= 0.0)) fail(weight_column, fmt::format("a point's weight must be >= 0, got {:g}", d.weight[i]));
    // Positive, then within the physical range of lang/limits.hpp.
    auto physical = [&](int column, const char* quantity, double value, double lowest, double highest, const char* unit) {
      if (!(value > 0.0)) fail(column, fmt::format("{} must be positive, got {:g} {}", quantity, value, unit));
      if (!(value >= lowest && value <= highest))
        fail(column, fmt::format("{} must lie between {:g} and {:g} {}, got {:g} {}; check the column's unit", quantity, lowest, highest, unit,
                                 value, unit));
    };
    physical(amplitude_column, "amplitude", d.amplitude[i], lang::min_amplitude, lang::max_amplitude, "mm");
    physical(d.frequency_column, "frequency", d.frequency[i], lang::min_frequency, lang::max_frequency, "Hz");
    physical(d.stiffness_column, "stiffness", d.stiffness[i], lang::min_stiffness, lang::max_stiffness, "N/mm");
    if (!(d.phase[i] > -std::numbers::pi / 2 && d.phase[i] <= std::numbers::pi / 2))
      fail(d.phase_column, fmt::format("phase must lie in (-90, 90] deg, got {:g} deg; check the column's unit (deg or rad) and sign convention",
                                       d.phase[i] * 180.0 / std::numbers::pi));
    const auto [it, fresh] = seen.emplace(std::make_pair(d.amplitude[i], d.frequency[i]), t.rows[i]);
    if (!fresh)
      fail(amplitude_column,
           fmt::format("duplicate point ({:g} mm, {:g} Hz), first at row {}; remove one", d.amplitude[i], d.frequency[i], it->second));
  }
  return d;
}

HarmonicData read_harmonic_data(const std::string& path) { return harmonic_data_from_table(read_table(path), DataReading{}); }

}  // namespace rheo::runtime
