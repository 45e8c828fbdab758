#include "runtime/io/harmonic_data.hpp"

#include "lang/limits.hpp"
#include "runtime/core/errors.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <numbers>
#include <utility>

namespace rheo::runtime {
namespace {

const std::vector<double>& need(const Table& t, const char* name, const char* alternative_hint) {
  const int c = t.column(name);
  if (c < 0)
    throw DataError(fmt::format("{}harmonic data need a column '{}'{}; add it ({})", header_error(t), name, alternative_hint, header_columns(t)));
  return t.columns[static_cast<std::size_t>(c)];
}

}  // namespace

HarmonicData harmonic_data_from_table(const Table& t) {
  HarmonicData d;
  d.path = t.path;
  d.amplitude = need(t, "amplitude", " [mm]");
  d.frequency = need(t, "frequency", " [Hz]");
  if (t.column("stiffness") >= 0 || t.column("storage") < 0) {
    d.stiffness = need(t, "stiffness", " [N/mm] (or storage and loss columns)");
    d.phase = need(t, "phase", " [deg]");
  } else {
    const auto& storage = need(t, "storage", " [N/mm]");
    const auto& loss = need(t, "loss", " [N/mm] next to storage");
    for (std::size_t i = 0; i < storage.size(); ++i) {
      d.stiffness.push_back(std::hypot(storage[i], loss[i]));
      d.phase.push_back(std::atan2(loss[i], storage[i]));
    }
  }
  d.rows = t.rows;
  const int weight_column = t.column("weight");
  d.weight = weight_column >= 0 ? t.columns[static_cast<std::size_t>(weight_column)] : std::vector<double>(d.size(), 1.0);
  std::map<std::pair<double, double>, int> seen;
  for (std::size_t i = 0; i < d.size(); ++i) {
    auto fail = [&](const char* column, const std::string& message) {
      throw DataError(fmt::format("{}:{}:{}: error: {} (column '{}')", t.path, t.rows[i], t.cell_column(i, t.column(column)), message, column));
    };
    if (!(d.weight[i] >= 0.0)) fail("weight", fmt::format("a point's weight must be >= 0, got {:g}", d.weight[i]));
    // Positive, then within the physical range of lang/limits.hpp.
    auto physical = [&](const char* column, const char* quantity, double value, double lowest, double highest, const char* unit) {
      if (!(value > 0.0)) fail(column, fmt::format("{} must be positive, got {:g} {}", quantity, value, unit));
      if (!(value >= lowest && value <= highest))
        fail(column, fmt::format("{} must lie between {:g} and {:g} {}, got {:g} {}; check the column's unit", quantity, lowest, highest, unit,
                                 value, unit));
    };
    physical("amplitude", "amplitude", d.amplitude[i], lang::min_amplitude, lang::max_amplitude, "mm");
    physical("frequency", "frequency", d.frequency[i], lang::min_frequency, lang::max_frequency, "Hz");
    physical(t.column("stiffness") >= 0 ? "stiffness" : "storage", "stiffness", d.stiffness[i], lang::min_stiffness, lang::max_stiffness, "N/mm");
    if (!(d.phase[i] > -std::numbers::pi / 2 && d.phase[i] <= std::numbers::pi / 2))
      fail(t.column("phase") >= 0 ? "phase" : "loss",
           fmt::format("phase must lie in (-90, 90] deg, got {:g} deg; check the column's unit (deg or rad) and sign convention",
                       d.phase[i] * 180.0 / std::numbers::pi));
    const auto [it, fresh] = seen.emplace(std::make_pair(d.amplitude[i], d.frequency[i]), t.rows[i]);
    if (!fresh)
      fail("amplitude", fmt::format("duplicate point ({:g} mm, {:g} Hz), first at row {}; remove one", d.amplitude[i], d.frequency[i], it->second));
  }
  return d;
}

HarmonicData read_harmonic_data(const std::string& path) { return harmonic_data_from_table(read_table(path)); }

}  // namespace rheo::runtime
