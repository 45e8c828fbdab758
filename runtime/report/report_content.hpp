// What a report shows, gathered from a fit, from measured data and a model, or from simulate
// results, before anything is drawn (html_report.hpp draws it). Units: amplitude mm,
// frequency Hz, stiffness N/mm, phase rad, displacement mm, force N; parameter values in the
// unit the model file wrote them in.
#pragma once

#include "lang/model.hpp"
#include "runtime/fit/fit.hpp"
#include "runtime/fit/fit_report.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/core/protocol_result.hpp"

#include <optional>
#include <string>
#include <vector>

namespace rheo::runtime::report {

// Model response on a harmonic grid, with the measurements when there are some.
struct HarmonicComparison {
  std::string label;  // the data file, or the protocol that produced the grid
  std::vector<double> amplitude, frequency, model_stiffness, model_phase;
  std::vector<double> measured_stiffness, measured_phase;  // empty: no measurements
  double phi = 0.0, err = 0.0;                             // eqs. 5.1, 6.1 when measured
  // An earlier model at the same points (the model before a diagnosis added an element); empty: none.
  std::vector<double> baseline_stiffness, baseline_phase;
  double baseline_err = 0.0;
  DataSource source{};  // how the file was read: its TRIOS step, the geometry of material data
  bool measured() const { return !measured_stiffness.empty(); }
  bool has_baseline() const { return !baseline_stiffness.empty(); }
  // The specimen's geometry when the data are material data with both area and height:
  // modulus [MPa] = stiffness [N/mm] x height / area, strain = amplitude / height.
  bool material() const { return source.material && source.area.value_or(0.0) > 0.0 && source.height.value_or(0.0) > 0.0; }
};

// A time history: force over displacement, model and (when given) measured.
struct HistoryComparison {
  std::string label;
  std::vector<double> displacement, model_force;
  std::vector<double> measured_force;  // empty: no measurements
  double rms = 0.0, worst = 0.0;       // (F - F_exp) / max|F_exp|: RMS and largest, when measured
  std::vector<double> baseline_force;  // an earlier model's force; empty: none
  double baseline_rms = 0.0;
  DataSource source{};
  ForceOffset offset{};       // the data line's force_offset: model_force includes `offset_value`
  double offset_value = 0.0;  // N, as declared or as fitted for model_force
  bool measured() const { return !measured_force.empty(); }
  bool has_baseline() const { return !baseline_force.empty(); }
};

struct ParameterRow {
  std::string path, unit;
  double value = 0.0;
  std::optional<double> start;  // fits: the start value
  std::string standard_error;   // fits: "1.13 (0.29 %)", "not identifiable", "-"; else empty
  std::string bounds;           // "[10, 5000]" for parameters declared with bounds
  bool free = false;            // fitted
};

// A section another command adds after the figures (e.g. a diagnosis: the gap before and after,
// what was added). `html` is trusted markup: its builder escapes what it embeds.
struct ReportSection {
  std::string id, title, html;
};

struct ReportContent {
  std::string title;  // "rheo fit: specimen_d"
  std::string model, source;
  std::string origin;  // what produced the results: "rheo fit, method exact, objective phi"
  lang::Element network;
  std::vector<ParameterRow> parameters;
  std::vector<HarmonicComparison> harmonic;
  std::vector<HistoryComparison> histories;
  std::vector<std::string> notes;
  std::vector<ReportSection> sections;
  std::string baseline;  // what the dashed curves are ("model before: ..."); empty: there are none
};

// The model's name, source, network and parameter values; no results yet.
ReportContent report_for_model(const Network& network, const std::string& source, const std::string& origin);

// After a fit: the fitted model against every data file of `data` (the fit's data, in order),
// parameters with start values, standard errors and bounds.
ReportContent report_from_fit(const FitResult& result, const std::vector<FitDataSet>& data, const FitDescription& description);

// SOURCE: how DATA was read (FitDataSet::source), shown in the report.
HarmonicComparison compare_harmonic(const HarmonicData& data, const std::vector<HarmonicPoint>& model, const DataSource& source = {});
HistoryComparison compare_history(const HistoryData& data, const std::vector<double>& model_force, const DataSource& source = {});
// The same for a measured data set and the model's prediction of it (its force offset named).
HistoryComparison compare_history(const FitDataSet& set, const Prediction& prediction);

// Adds `earlier`'s predictions as the baseline of every data set of `content` (which must come
// from report_from_fit on the same data, in order), described as `what`.
void add_baseline(ReportContent& content, const FitResult& earlier, const std::string& what);

// Adds a simulate protocol's result, labelled LABEL: a harmonic grid or a history.
void add_simulation_result(ReportContent& content, const std::string& label, const ProtocolResult& result);

}  // namespace rheo::runtime::report
