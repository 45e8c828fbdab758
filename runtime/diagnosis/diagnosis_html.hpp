// The HTML report of `rheo diagnose` and `rheo refine` (`--report`, drawn by
// report/html_report.hpp):
//   - the final model (the last round's refit, or the model as fitted when nothing was added)
//     against the data: its curves as lines, the model before the first round as dashed
//     curves, and residual maps of both on shared colour scales;
//   - a section "Diagnosis" (one round) or "Refinement" (several): a table of the gap (err,
//     eq. 6.1, or the RMS force residual) as fitted and after every round, with how many times
//     lower and a bar per row, then per round where the model missed, the candidates tried
//     (screened share, refitted gap, BIC, element), the effect named and why, and the lines
//     added to the model;
//   - the network before the first round, as a figure of kind "network-before", when an
//     element was added.
#pragma once

#include "runtime/diagnosis/diagnose.hpp"
#include "runtime/fit/fit_report.hpp"
#include "runtime/report/report_content.hpp"

#include <string>
#include <vector>

namespace rheo::runtime::diagnosis {

// `rounds`: the diagnoses in order, each on the previous one's refined model (one for
// `rheo diagnose`); `data`: the data sets they were fitted to, in order; `command`: "rheo
// diagnose" or "rheo refine". Throws std::logic_error when `rounds` is empty.
report::ReportContent diagnosis_report_content(const std::vector<Diagnosis>& rounds, const std::vector<FitDataSet>& data,
                                               const FitDescription& description, const std::string& command);

}  // namespace rheo::runtime::diagnosis
