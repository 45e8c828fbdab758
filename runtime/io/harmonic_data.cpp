#include "runtime/io/harmonic_data.hpp"

#include "lang/limits.hpp"
#include "lang/text_encoding.hpp"
#include "runtime/core/errors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

namespace rheo::runtime {
namespace {

// Equal within the relative tolerance of repeated points.
bool same_value(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b)); }

// Classes of VALUES[I] for I in INDICES: values within same_value of a class's smallest are one
// class. Sets CLASS_OF[I], numbering the classes on from NEXT (which ends at the last one).
void classify(const std::vector<double>& values, std::vector<std::size_t> indices, std::vector<std::size_t>& class_of, std::size_t& next) {
  std::sort(indices.begin(), indices.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  double first = 0.0;
  for (std::size_t k = 0; k < indices.size(); ++k) {
    if (k == 0 || !same_value(first, values[indices[k]])) {
      first = values[indices[k]];
      ++next;
    }
    class_of[indices[k]] = next;
  }
}

// "rows 4, 9 and 12".
std::string row_list(const std::vector<int>& rows) {
  std::string out = "rows ";
  for (std::size_t k = 0; k < rows.size(); ++k) out += fmt::format("{}{}", k == 0 ? "" : k + 1 == rows.size() ? " and " : ", ", rows[k]);
  return out;
}

// Groups D's points at the same (amplitude, frequency) within same_value. Each group of two or
// more becomes one point at its first row: the mean complex stiffness (storage K cos(phase),
// loss K sin(phase)) as K and phase, the mean weight, the first row's amplitude and frequency;
// a note names the rows. With DuplicatePoints::error a group is a DataError at its second row.
void merge_repeated_points(HarmonicData& d, lang::DuplicatePoints mode, const Table& t, int amplitude_column) {
  const std::size_t n = d.size();
  std::vector<std::size_t> all(n), amplitude_class(n), point_class(n);
  for (std::size_t i = 0; i < n; ++i) all[i] = i;
  std::size_t classes = 0;
  classify(d.amplitude, all, amplitude_class, classes);
  std::map<std::size_t, std::vector<std::size_t>> by_amplitude;
  for (std::size_t i = 0; i < n; ++i) by_amplitude[amplitude_class[i]].push_back(i);
  classes = 0;
  std::vector<std::size_t> frequency_class(n);
  for (const auto& [amplitude, members] : by_amplitude) classify(d.frequency, members, frequency_class, classes);
  std::map<std::size_t, std::vector<std::size_t>> by_frequency;
  for (std::size_t i = 0; i < n; ++i) by_frequency[frequency_class[i]].push_back(i);
  classes = 0;
  for (const auto& [frequency, members] : by_frequency) classify(d.preload, members, point_class, classes);  // p = 0 for most tables
  std::map<std::size_t, std::vector<std::size_t>> groups;                                                    // members in row order
  for (std::size_t i = 0; i < n; ++i) groups[point_class[i]].push_back(i);

  std::vector<bool> keep(n, true);
  for (const auto& [point, members] : groups) {
    if (members.size() < 2) continue;
    const std::size_t first = members.front();
    std::vector<int> rows;
    for (std::size_t i : members) rows.push_back(d.rows[i]);
    const std::string where = d.preload[first] == 0.0
                                  ? fmt::format("({:g} mm, {:g} Hz)", d.amplitude[first], d.frequency[first])
                                  : fmt::format("({:g} mm, {:g} Hz, preload {:g} mm)", d.amplitude[first], d.frequency[first], d.preload[first]);
    if (mode == lang::DuplicatePoints::error) {
      const std::size_t second = members[1];
      const std::string message = fmt::format("duplicate point {}, first at row {}; remove one, or average them with duplicates = average", where,
                                              d.rows[first]);
      if (amplitude_column < 0) throw DataError(fmt::format("{}:{}:1: error: {}", t.path, d.rows[second], message));
      throw DataError(fmt::format("{}:{}:{}: error: {} (column '{}')", t.path, d.rows[second], t.cell_column(second, amplitude_column), message,
                                  lang::printable(t.names[static_cast<std::size_t>(amplitude_column)])));
    }
    double storage = 0.0, loss = 0.0, weight = 0.0;
    for (std::size_t i : members) {
      storage += d.stiffness[i] * std::cos(d.phase[i]);
      loss += d.stiffness[i] * std::sin(d.phase[i]);
      weight += d.weight[i];
      if (i != first) keep[i] = false;
    }
    const auto count = static_cast<double>(members.size());
    const double stiffness = std::hypot(storage, loss) / count;
    if (!(stiffness >= lang::min_stiffness))
      throw DataError(fmt::format("{}:{}:1: error: {} repeat {} and their complex stiffnesses cancel (mean {:g} N/mm); check those rows", t.path,
                                  d.rows[first], row_list(rows), where, stiffness));
    d.stiffness[first] = stiffness;
    d.phase[first] = std::atan2(loss, storage);
    d.weight[first] = weight / count;
    d.notes.push_back(fmt::format("{}:{}: {} repeat {}: averaged into one point (mean storage and loss stiffness)", t.path, d.rows[first],
                                  row_list(rows), where));
  }
  if (d.notes.empty()) return;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!keep[i]) continue;
    d.amplitude[kept] = d.amplitude[i];
    d.frequency[kept] = d.frequency[i];
    d.stiffness[kept] = d.stiffness[i];
    d.phase[kept] = d.phase[i];
    d.weight[kept] = d.weight[i];
    d.preload[kept] = d.preload[i];
    d.rows[kept] = d.rows[i];
    ++kept;
  }
  for (auto* column : {&d.amplitude, &d.frequency, &d.stiffness, &d.phase, &d.weight, &d.preload}) column->resize(kept);
  d.rows.resize(kept);
}

}  // namespace

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
  const int preload_column = find_role(t, Role::preload, how);
  d.preload = preload_column >= 0 ? role_values(t, preload_column, Role::preload, how) : std::vector<double>(d.size(), 0.0);
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
    if (!(std::abs(d.preload[i]) <= lang::max_amplitude))
      fail(preload_column,
           fmt::format("preload {:g} mm is beyond the {:g} mm a rig can drive; check the column's unit", d.preload[i], lang::max_amplitude));
    // Above a resonance the phase passes 90 deg (thesis: 180 deg - asin d; first harmonic: arg K*).
    if (!(d.phase[i] > -std::numbers::pi / 2 && d.phase[i] <= std::numbers::pi))
      fail(d.phase_column, fmt::format("phase must lie in (-90, 180] deg, got {:g} deg; check the column's unit (deg or rad) and sign convention",
                                       d.phase[i] * 180.0 / std::numbers::pi));
  }
  merge_repeated_points(d, reading.duplicates, t, amplitude_column);
  return d;
}

HarmonicData read_harmonic_data(const std::string& path) { return harmonic_data_from_table(read_table(path), DataReading{}); }

}  // namespace rheo::runtime
