#include "lang/protocol_settings.hpp"

#include "lang/fit_settings.hpp"

#include <array>
#include <utility>

namespace rheo::lang {
namespace {

// One table per vocabulary: the words the language (and the command line) accepts, for the
// protocols' settings and the fit block's (fit_settings.hpp).
template <class E, std::size_t N>
using Words = std::array<std::pair<E, std::string_view>, N>;

constexpr Words<HarmonicDefinition, 2> definitions{{{HarmonicDefinition::thesis, "thesis"}, {HarmonicDefinition::first_harmonic, "first_harmonic"}}};
constexpr Words<SteadyState, 3> steady_states{
    {{SteadyState::automatic, "auto"}, {SteadyState::closed_form, "closed_form"}, {SteadyState::time_stepping, "time_stepping"}}};
constexpr Words<SolverChoice, 3> solvers{{{SolverChoice::automatic, "auto"}, {SolverChoice::fixed, "fixed"}, {SolverChoice::sundials, "sundials"}}};
constexpr Words<OutputFormat, 2> formats{{{OutputFormat::csv, "csv"}, {OutputFormat::json, "json"}}};
constexpr Words<HistoryStart, 2> starts{{{HistoryStart::relaxed, "relaxed"}, {HistoryStart::rest, "rest"}}};
constexpr Words<FitObjective, 2> objectives{{{FitObjective::phi, "phi"}, {FitObjective::least_squares, "least_squares"}}};
constexpr Words<FitMethod, 3> methods{{{FitMethod::exact, "exact"}, {FitMethod::approximate, "approximate"}, {FitMethod::corrected, "corrected"}}};
constexpr Words<Optimizer, 8> optimizers{{{Optimizer::automatic, "default"},
                                          {Optimizer::bobyqa, "bobyqa"},
                                          {Optimizer::sbplx, "sbplx"},
                                          {Optimizer::neldermead, "neldermead"},
                                          {Optimizer::direct_l, "direct_l"},
                                          {Optimizer::crs2, "crs2"},
                                          {Optimizer::isres, "isres"},
                                          {Optimizer::mlsl, "mlsl"}}};
constexpr Words<DuplicatePoints, 2> duplicate_points{{{DuplicatePoints::average, "average"}, {DuplicatePoints::error, "error"}}};

template <class E, std::size_t N>
std::string_view word_in(const Words<E, N>& table, E value) {
  for (const auto& [v, w] : table)
    if (v == value) return w;
  return "?";
}

template <class E, std::size_t N>
std::optional<E> named_in(const Words<E, N>& table, std::string_view word) {
  for (const auto& [v, w] : table)
    if (w == word) return v;
  return std::nullopt;
}

template <class E, std::size_t N>
std::vector<std::string> all_words(const Words<E, N>& table) {
  std::vector<std::string> out;
  for (const auto& entry : table) out.emplace_back(entry.second);
  return out;
}

}  // namespace

std::vector<std::string> harmonic_definition_words() { return all_words(definitions); }
std::vector<std::string> steady_state_words() { return all_words(steady_states); }
std::vector<std::string> solver_choice_words() { return all_words(solvers); }
std::vector<std::string> output_format_words() { return all_words(formats); }
std::vector<std::string> history_start_words() { return all_words(starts); }

std::string_view word_of(HarmonicDefinition value) { return word_in(definitions, value); }
std::string_view word_of(SteadyState value) { return word_in(steady_states, value); }
std::string_view word_of(SolverChoice value) { return word_in(solvers, value); }
std::string_view word_of(OutputFormat value) { return word_in(formats, value); }
std::string_view word_of(HistoryStart value) { return word_in(starts, value); }

std::optional<HarmonicDefinition> harmonic_definition_named(std::string_view word) { return named_in(definitions, word); }
std::optional<SteadyState> steady_state_named(std::string_view word) { return named_in(steady_states, word); }
std::optional<SolverChoice> solver_choice_named(std::string_view word) { return named_in(solvers, word); }
std::optional<OutputFormat> output_format_named(std::string_view word) { return named_in(formats, word); }
std::optional<HistoryStart> history_start_named(std::string_view word) { return named_in(starts, word); }

std::string_view word_of(FitObjective value) { return word_in(objectives, value); }
std::string_view word_of(FitMethod value) { return word_in(methods, value); }
std::string_view word_of(Optimizer value) { return word_in(optimizers, value); }
std::vector<std::string> fit_objective_words() { return all_words(objectives); }
std::vector<std::string> fit_method_words() { return all_words(methods); }
std::vector<std::string> optimizer_words() { return all_words(optimizers); }
std::optional<FitObjective> fit_objective_named(std::string_view word) { return named_in(objectives, word); }
std::optional<FitMethod> fit_method_named(std::string_view word) { return named_in(methods, word); }
std::optional<Optimizer> optimizer_named(std::string_view word) { return named_in(optimizers, word); }
std::string_view word_of(DuplicatePoints value) { return word_in(duplicate_points, value); }
std::vector<std::string> duplicate_points_words() { return all_words(duplicate_points); }
std::optional<DuplicatePoints> duplicate_points_named(std::string_view word) { return named_in(duplicate_points, word); }

}  // namespace rheo::lang
