// The settings of a fit block, typed, with the language's defaults for what the block leaves
// out (docs/language.md, "fit"). The checker decodes a block into these (fit_schema.hpp); the
// command line may override some of them (rheo fit --method, --optimizer, ...).
#pragma once

#include "lang/protocol_settings.hpp"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rheo::lang {

enum class FitObjective { phi, least_squares };          // `objective`: eq. 5.38, or squared relative residuals
enum class FitMethod { exact, approximate, corrected };  // `method`: time stepping, eq. 5.4's approximation, or both
enum class Optimizer { automatic, bobyqa, sbplx, neldermead, direct_l, crs2, isres, mlsl };  // `optimizer` ("default": automatic)
// A data line's `duplicates`: points of a harmonic table at the same (amplitude, frequency),
// relative 1e-9, averaged into one, or an error.
enum class DuplicatePoints { average, error };

std::string_view word_of(FitObjective value);
std::string_view word_of(FitMethod value);
std::string_view word_of(Optimizer value);
std::string_view word_of(DuplicatePoints value);
std::vector<std::string> fit_objective_words();
std::vector<std::string> fit_method_words();
std::vector<std::string> optimizer_words();
std::vector<std::string> duplicate_points_words();
std::optional<FitObjective> fit_objective_named(std::string_view word);
std::optional<FitMethod> fit_method_named(std::string_view word);
std::optional<Optimizer> optimizer_named(std::string_view word);
std::optional<DuplicatePoints> duplicate_points_named(std::string_view word);

struct FitSettings {
  FitObjective objective = FitObjective::phi;
  std::optional<double> stiffness_weight;  // k of eq. 5.38: w_K = k, w_d = 1 - k; absent: both weights 1
  FitMethod method = FitMethod::exact;
  Optimizer optimizer = Optimizer::automatic;
  // Absent: the search's own defaults (runtime/fit/fit_search.hpp, SearchSettings).
  std::optional<int> max_evaluations;
  std::optional<int> starts;
  std::optional<double> tolerance;   // relative, on the scaled parameters
  std::optional<double> time_limit;  // [s] wall clock of the whole fit (runtime FitSettings::time_limit)
  int seed = 1;
  HarmonicDefinition definition = HarmonicDefinition::thesis;
  std::optional<int> steps_per_cycle;  // absent: HarmonicSettings::default_steps_per_cycle (rheo diagnose takes 128)
  SolverChoice solver = SolverChoice::automatic;
};

}  // namespace rheo::lang
