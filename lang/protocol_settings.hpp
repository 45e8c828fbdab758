// The settings of each simulate protocol, typed, with the language's defaults for the settings a
// block leaves out (docs/language.md lists them). The checker decodes a protocol line into one of
// these (protocol_schema.hpp); nothing downstream reads a setting by its key.
//
// Values are in the internal unit system of model.hpp: lengths mm, times s, frequencies Hz,
// velocities mm/s.
#pragma once

#include "lang/source_location.hpp"

#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace rheo::lang {

// The vocabularies of the identifier settings, shared by protocols, fit blocks and the command
// line (each has a word table in protocol_settings.cpp).
enum class HarmonicDefinition { thesis, first_harmonic };          // `definition`: eqs. 5.26-5.27, or K' and K''
enum class SteadyState { automatic, closed_form, time_stepping };  // `steady_state`
enum class SolverChoice { automatic, fixed, sundials };            // `solver` (runtime/protocols/solver_choice.hpp)
enum class OutputFormat { csv, json };                             // `format`
enum class HistoryStart { relaxed, rest };                         // `start` of a history (runtime/stepping/relaxed_state.hpp)

// A header column named for a role: `columns = "frequency = f"` (docs/data-formats.md); in an
// HDF5 file a dataset's path, optionally with its unit: `time = /rig/t [ms]`.
struct ColumnName {
  std::string role;  // one of data_column_roles() (fit_schema.hpp)
  std::string name;  // the header's name, as written
  bool operator==(const ColumnName&) const = default;
};

std::string_view word_of(HarmonicDefinition value);
std::string_view word_of(SteadyState value);
std::string_view word_of(SolverChoice value);
std::string_view word_of(OutputFormat value);
std::string_view word_of(HistoryStart value);
// Every word of a vocabulary, in table order (schemas and command-line choices).
std::vector<std::string> harmonic_definition_words();
std::vector<std::string> steady_state_words();
std::vector<std::string> solver_choice_words();
std::vector<std::string> output_format_words();
std::vector<std::string> history_start_words();
// The value a word names; nullopt when it names none.
std::optional<HarmonicDefinition> harmonic_definition_named(std::string_view word);
std::optional<SteadyState> steady_state_named(std::string_view word);
std::optional<SolverChoice> solver_choice_named(std::string_view word);
std::optional<OutputFormat> output_format_named(std::string_view word);
std::optional<HistoryStart> history_start_named(std::string_view word);

// Settings every protocol accepts.
struct CommonSettings {
  bool elements = false;  // `elements = all`: histories add every element's force and elongation
  OutputFormat format = OutputFormat::csv;
  SolverChoice solver = SolverChoice::automatic;
};

// `harmonic`: the periodic steady state at every amplitude x frequency of the grid.
struct HarmonicSettings : CommonSettings {
  static constexpr int default_steps_per_cycle = 2048;  // a multiple of 4: the turning points are samples
  static constexpr int default_cycles_max = 400;
  static constexpr double default_tolerance = 1e-9;  // relative change of a cycle's measures
  std::vector<double> frequencies;                   // Hz, each > 0 (required)
  std::vector<double> amplitudes;                    // mm, each > 0 (required)
  HarmonicDefinition definition = HarmonicDefinition::thesis;
  SteadyState steady_state = SteadyState::automatic;
  int steps_per_cycle = default_steps_per_cycle;
  int cycles_max = default_cycles_max;
  double tolerance = default_tolerance;
  double preload = 0.0;  // mm, any sign: the mean displacement p, u = p + u0 sin(2 pi f t)
};

// `static`: a triangle of constant rate per amplitude (the thesis's static test).
struct StaticSettings : CommonSettings {
  static constexpr int samples_per_cycle = 400;  // without dt
  double velocity = 0.0;                         // mm/s (required)
  std::vector<double> amplitudes;                // mm (required)
  int cycles = 2;                                // per amplitude
  std::optional<double> dt;                      // s: a fixed sample interval instead
};

// `quasistatic`: a slow sine per amplitude.
struct QuasistaticSettings : CommonSettings {
  double frequency = 0.0;          // Hz (required)
  std::vector<double> amplitudes;  // mm (required)
  int cycles = 2;                  // per amplitude
  int steps_per_cycle = 400;
};

// `history`: a displacement history read from a table.
struct HistorySettings : CommonSettings {
  std::string file;                 // as written: relative to the .rheo file (required)
  SourceLocation file_where;        // of the file name, for the reader's errors
  std::vector<ColumnName> columns;  // `columns`: the time and displacement columns (HDF5: datasets)
  int substeps = 1;                 // each sample interval cut into this many linear parts
  // relaxed: the network starts relaxed at the first sample's displacement; rest: from rest,
  // which needs displacement 0 in the first row.
  HistoryStart start = HistoryStart::relaxed;
};

// `step`: a ramp to `amplitude` over `rise`, then held (relaxation).
struct StepSettings : CommonSettings {
  double amplitude = 0.0;  // mm, may be negative (required)
  double duration = 0.0;   // s (required)
  double dt = 0.0;         // s; default duration / 1000
  double rise = 0.0;       // s; default dt
};

using ProtocolSettings = std::variant<HarmonicSettings, StaticSettings, QuasistaticSettings, HistorySettings, StepSettings>;

inline CommonSettings& common(ProtocolSettings& settings) {
  return std::visit([](CommonSettings& c) -> CommonSettings& { return c; }, settings);
}
inline const CommonSettings& common(const ProtocolSettings& settings) {
  return std::visit([](const CommonSettings& c) -> const CommonSettings& { return c; }, settings);
}

}  // namespace rheo::lang
