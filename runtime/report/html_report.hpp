// A report as one self-contained HTML page: inline CSS (with print styles) and inline SVG, no
// script, no external reference of any kind (no URL, font, image or style sheet is fetched), so
// that it opens from disk offline. Sections: title (model, source file, what produced it);
// summary (per data set phi (5.1) and err (6.1), or the force residual of a history; notes);
// the network diagram; the parameter table (units; for fits start values, standard errors
// and bounds); per data set how its file was read when that was more than a plain table (its
// TRIOS step; for material data the geometry, area and height), then for a harmonic grid its
// plots and residual maps, for a history its hysteresis loop (report_figures.hpp); then
// ReportContent::sections (e.g. a diagnosis) in order.
// Every figure is <figure class="plot" data-figure="KIND"> with KIND one of
// stiffness-frequency, phase-frequency, stiffness-amplitude, phase-amplitude, storage-frequency,
// loss-frequency, storage-amplitude, loss-amplitude (harmonic_plots), residual-stiffness, residual-phase, residual-stiffness-before, residual-phase-before (with a
// baseline), hysteresis, network. ReportContent::sections may add figures of their own kinds.
#pragma once

#include "runtime/report/report_content.hpp"

#include <string>

namespace rheo::runtime::report {

std::string html_report(const ReportContent& content);

// One <figure class="plot" data-figure="KIND"> around an inline SVG, with its caption (escaped
// here); for ReportSection::html.
std::string figure_html(const std::string& kind, const std::string& svg, const std::string& caption);

}  // namespace rheo::runtime::report
