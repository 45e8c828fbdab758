// What `rheo diagnose` tells people and programs: a plain-text report and a JSON summary.
//
// JSON (one object):
//   effect: "amplitude-dependence" | "rate-dependence" | "nonlinear-elasticity" |
//           "coupled-amplitude-frequency" | "inertia" | "none" | "unexplained" (the verdict,
//           diagnose.hpp: none is a residual at the noise, unexplained one beyond it that no
//           candidate removes)
//   alike: [effect...]: for a named effect, the other effects whose refitted candidate earned
//           and fits within the parsimony margin of its gap (the data do not tell them apart;
//           diagnose.hpp Diagnosis::alike); [] otherwise
//   evidence: {reason, patterns: [text...], harmonic?: {points, stiffness_rms, phase_rms_deg,
//              amplitude_share, frequency_share, interaction_share, interaction_measured (false: the
//              grid cannot measure it, the share is 0 and coupling is not screened), worst_stiffness: {amplitude_mm,
//              frequency_hz, residual}, worst_phase: {amplitude_mm, frequency_hz, residual_deg},
//              phase_peak: {frequency_hz, excess_deg}}, histories: [{file, rms, max, worst_displacement_mm}],
//              candidates: [{effect, screened_gain, element, trial, refitted, gap_after?,
//              criterion?, parameters?, wall_seconds?, fitted? (the added element's refitted values),
//              unresolved?}]  (unresolved: why a
//              refitted resonance cannot earn),
//              noise: null | {floor (the gap noise alone leaves), relative_error, ratio (the gap
//              over it, for the model's degrees of freedom), pseudo_residuals, stiffness?,
//              phase_deg? (harmonic: RMS noise), force?, autocorrelation? (histories)}}
//              (noise_estimate.hpp)
//   gap_measure: "err (6.1)" | "RMS force residual";  err_before, err_after (that measure)
//   criterion: {name: "BIC", residual_terms, before, after?}
//   added: [] | [{element, effect, statement: [lines], parameters: [{path, value, unit}]}]
//   at_bounds: [text...]: the refitted model's free parameters at a bound (fit_report.hpp's
//              bound_notes; the text report lists them under the added element), [] for none
//   model: the refined .rheo text (fitted values; the added element with its comment)
//   model_name, source, output (the path written, or null), interrupted, time_limited
//   unexplained: null | {reason, amplitudes, frequencies: null | {low_mm|low_hz, high_mm|high_hz,
//              share, levels} (the narrowest run of levels holding half the squared residual),
//              resembles: null | text, resembles_share (histories), best_candidate: null |
//              {effect, trial, gap_after, criterion, parameters}}  (unexplained.hpp)
#pragma once

#include "runtime/diagnosis/diagnose.hpp"

#include <string>

namespace rheo::runtime::diagnosis {

std::string diagnosis_report_text(const std::string& source_file, const Diagnosis& diagnosis);
std::string diagnosis_report_json(const std::string& source_file, const Diagnosis& diagnosis, const std::string& output);

}  // namespace rheo::runtime::diagnosis
