// What `rheo fit` tells people and programs about a fit: a plain-text report and a JSON
// summary. Parameter values are given in the unit the model file wrote them in (internal unit
// when it wrote none); phases in degrees; err is eq. 6.1, phi eq. 5.1.
//
// JSON summary (one object per fit):
//   model, source, method, objective, optimizer, seed, status, interrupted, evaluations,
//   non_finite_evaluations, first_failure (why the first evaluation that could not be simulated
//   failed; "" when none), wall_seconds, phi, err, notes: [text...] (FitResult::notes),
//   parameters: [{path, unit, start (where the search started), start_from ("yeoh": the yeoh start
//                 from a history's mean curve set it; "given": the model's value, or --yeoh-start's), value,
//                 lower, upper, free, standard_error, identifiable,
//                 at_bound? ("lower" | "upper": a free parameter at a bound, parameter_bounds.hpp)}],
//   correlation: {parameters: [path...], matrix: [[...]]}  (free parameters),
//   data: [{file, kind, weight, points, err, phi?, step?, area_mm2?, height_mm? (material data),
//           force_offset? (a history whose data line sets it: {value [N], unit "N", free,
//             standard_error? [N], identifiable?, correlation? [with each free parameter, in
//             correlation.parameters' order]}; the last three for a fitted (free) offset),
//           residuals: [{amplitude_mm, frequency_hz,
//           stiffness_measured, stiffness_model, phase_measured_deg, phase_model_deg,
//           stiffness_residual, damping_residual}] | {rms, max}}]
// Every parameter of the model is listed; lower/upper only for those with bounds,
// identifiable only for free ones, standard_error only where it is finite (not for a
// non-identifiable parameter, nor after an interrupted fit, which has no statistics). A
// correlation entry that is not defined (NaN) is written as null. The text report lists a
// fitted offset in the parameter table as `data FILE: force_offset` (start 0, unit N, no bounds).
#pragma once

#include "runtime/fit/fit.hpp"

#include <string>
#include <vector>

namespace rheo::runtime {

// "; TRIOS step "Amplitude sweep - 1"; material data: stiffness = modulus x 490.9 mm^2 / 1 mm,
// ...": how a data set's values were read, "" for a plain table.
std::string source_text(const DataSource& source);

struct FitDescription {
  std::string source;     // the .rheo file
  std::string method;     // "exact", "approximate", "corrected"
  std::string objective;  // "phi", "least_squares"
  std::string optimizer;  // "default" or the algorithm's name
  unsigned long seed = 1;
};

std::string fit_report_text(const FitDescription& description, const FitResult& result);
std::string fit_report_json(const FitDescription& description, const FitResult& result);

// "m3.tau = 9999.93 ms is at its upper bound 10000: widen it?" for each free parameter at a
// bound (parameter_bounds.hpp), in the order of FitResult::free. The text report flags them
// in its table ("at a bound: widen it?").
std::vector<std::string> bound_notes(const FitResult& result);

// Parameter value in the unit the model wrote (Parameter::unit), or the internal unit.
double in_written_unit(const lang::Parameter& parameter, double internal_value);
std::string written_unit(const lang::Parameter& parameter);

}  // namespace rheo::runtime
