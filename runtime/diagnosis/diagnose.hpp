// `rheo diagnose` without the command line: fit a model, find where it and the measurement
// disagree, name the missing effect, add the element that supplies it and refit.
//
//   1. Fit the model (its free parameters, method exact) to the data: the gap before.
//   2. Describe the residual (patterns.hpp) and screen every effect (screen.hpp): the share of
//      the objective the best element of its family would remove alone.
//   3. Confirm the leading effects (at most `confirm`, screening gain >= `min_screen_gain` and
//      >= `relative_screen_gain` times the leading one's), and the offset wherever it is screened
//      (offset_candidate.hpp: the histories' force offsets made free and every free parameter
//      refitted by one local search; a constant that a preload's static force takes up as fitted
//      screens low):
//      write the element into the fitted model's source with bounds, compile it and refit in
//      two stages: the new parameters alone, sampled over the range the data support and
//      searched locally from the best samples and the screened element, then every free
//      parameter together from the best of those and from the screened element (refit.hpp).
//      Of the refitted slider-capped Maxwell arms slower than the drives stick them
//      (candidate_model.hpp longest_stick), the one of the lowest gap is refitted once more as
//      its limit tau -> infinity, a friction element (candidate_model.hpp friction_limit); and
//      such an arm's refit is searched again from each root friction element's roles exchanged
//      with its own (candidate_model.hpp roles_exchanged).
//   4. Choose by the Bayesian information criterion over the N residual terms of the fit,
//        BIC = -2 ln L + p ln(N),   p the free parameters (criterion.hpp): on harmonic data with
//      a noise estimate, -2 ln L is the chi^2 of the residuals under the estimated stiffness and
//      phase noise; else N ln(J), J the minimised objective, the noise's size profiled out;
//      so that a larger model must earn its parameters: a candidate earns when its BIC is below
//      the model's and it lowers the gap (or where weighted its residual over the noise,
//      criterion.hpp lowers_residual) by at least `min_improvement`. Of those that earn, the
//      one with fewer parameters wins if its gap is within `parsimony` of the other's, unless
//      the other's noise-weighted BIC is decisively lower (criterion.hpp decisively_lower, both
//      judged at their likelihood's maximum); else the lower BIC (where noise-weighted, both
//      at their likelihood's maximum too, and the richer only where its BIC is positively
//      lower, criterion.hpp positively_lower). Where none earns but free
//      play and asymmetry were both refitted, play in
//      front of a friction element made one-sided is refitted as one more candidate. Where still
//      none earns and the residual lies beyond the noise, the leading refitted shapes (one per
//      shape, lowest gap first, at most `confirm`) are fitted as the model was in step 1: every
//      free parameter by the fit's own strategy, from the file's start values (step 1's fit may
//      have taken the missing effect into the model's own elements, which no search from it
//      gives back).
//      A resonance (the fluid-column shapes) earns only where the measurement
//      resolves it: refitted to f_r = sqrt(k/b)/(2 pi), a measured frequency must lie at least
//      10 % below and one 10 % above it; at the edge of the data a resonance is a relaxation's
//      rising stiffness with one more parameter. None earns: nothing is added, and the verdict
//      is `none` when the gap is indistinguishable from the measurement noise estimated from the
//      residual (noise_estimate.hpp), else `unexplained`, with the residual's shape
//      (unexplained.hpp) and the best candidate's numbers. Where the criterion is noise-
//      weighted, the fits minimise eq. 5.1, not chi^2, and a fit's chi^2 is not the likelihood
//      at its maximum, which the BIC takes: the model's chi^2, and that of each candidate that
//      lowers the gap enough to earn but whose fit's chi^2 does not earn already (an upper bound
//      of its least), are minimised from their fits (criterion.hpp least_chi_square), and the model's least chi^2 over N - p, not the gap over the floor,
//      tells noise from a systematic residual (on pure noise the gap of a fit drawn to a few
//      nearly elastic points' phase noise was twice the floor, at chi^2 / (N - p) = 0.46); the
//      noise is estimated again on the residual at the model's least chi^2 (criterion.hpp
//      noise_at_likelihood_maximum), and a candidate's gain to the noise is judged by the same
//      measure (criterion.hpp reaches_noise).
//   5. Polish the chosen model: Levenberg-Marquardt over every free parameter again with the
//      refit's budget, at least 10 Jacobians (refit.hpp kLocalJacobians), ended where a
//      Jacobian's step gains less than kPolishCrawl of the objective; gap_after is the
//      polished model's (with its standard errors when `standard_errors`).
// The gap is err (eq. 6.1) over the harmonic points when there are any, else the RMS over the
// history files of their RMS force residual relative to max|F_exp|.
#pragma once

#include "runtime/diagnosis/noise_estimate.hpp"
#include "runtime/diagnosis/patterns.hpp"
#include "runtime/diagnosis/screen.hpp"
#include "runtime/diagnosis/unexplained.hpp"
#include "runtime/fit/fit.hpp"

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rheo::runtime::diagnosis {

struct ModelSource {
  std::string file;   // as given: names the source in messages and comments
  std::string text;   // the file's contents
  std::string model;  // the model to diagnose
  // The fit block (index into the fits TEXT compiles to) whose data lines the data were read
  // from, one line per data set: where a fitted force offset is written (offset_candidate.hpp);
  // -1 when the data came from elsewhere (--data).
  int fit_block = -1;
};

struct DiagnoseSettings {
  FitSettings fit;                     // every fit (the method is always exact; the solver as diagnosis_solver says)
  std::vector<std::string> free;       // paths of the model's free parameters; empty: every one with bounds
  int confirm = 3;                     // leading effects refitted
  double min_screen_gain = 0.01;       // effects screened below this are not refitted,
  double relative_screen_gain = 0.25;  // nor those below this share of the leading effect's gain
  // Relative drop of the gap a chosen candidate must bring. BIC without a noise estimate takes
  // the residuals as iid, but relative damping residuals at small phases are not: a narrow
  // resonance (3 parameters) fitted noise at one frequency for a 13 % drop on data the model
  // explained.
  double min_improvement = 0.25;
  double parsimony = 0.1;  // a candidate with fewer parameters wins if its gap is within this of another's
  // Budgets. A refit may spend `refit_work` time steps (refit.cpp evaluation_work: counted on
  // the candidate's first prediction, not timed), at most `max_evaluations` per stage. Stage 1
  // first looks over the range the data support for the new parameters (global_look.hpp):
  // `global_samples` points per new parameter, up to four times that where the work budget
  // affords a quarter of it; then Levenberg-Marquardt over the new parameters from the screened
  // element and the `global_starts` - 1 best points, the best result kept. Stage 2 runs
  // Levenberg-Marquardt over every free parameter from the best of stage 1 and from the
  // screened element as sized, each with a quarter of the budget, at least 10 Jacobians
  // (10 (n + 1) evaluations). Where the budget affords `thorough_evaluations` per parameter of
  // both stages, the local searches of stage 1 share half of it, else each gets 10 (n + 1) for n
  // new parameters. The polish gets the refit's budget, at least 10 (n + 1).
  double refit_work = 1e7;
  int max_evaluations = 20000;
  int thorough_evaluations = 100;
  int global_samples = 10;
  int global_starts = 3;
  // Standard errors of the model as fitted and of the refined one (reports show them); each
  // costs 2 n + 1 evaluations, which for time-stepped models is seconds.
  bool standard_errors = false;
  std::function<void(const std::string&)> stage;  // told what runs next ("refitting ..."); may be empty
  // Wall-clock bound of the whole diagnosis: the model's fit may take a third of the time left,
  // each candidate's refit an equal share of what is left then (the polish one more), and what
  // has not begun by the deadline is skipped; the result so far (Diagnosis::time_limited).
  std::optional<std::chrono::steady_clock::time_point> deadline;
};

// What the diagnosis concludes: an effect named (its element added), `none` (the gap is
// indistinguishable from the measurement noise) or `unexplained` (the residual is more than the
// noise, but no candidate earns its parameters).
enum class Verdict { named, none, unexplained };

struct CandidateOutcome {
  ScreenedEffect screened;
  bool refitted = false;
  std::string element;     // name of the added (or replacing) element
  double gap_after = 0.0;  // after the two-stage refit (before any polish)
  double criterion = 0.0;  // BIC of the refitted model
  // Whether `criterion` is at the likelihood's maximum (criterion.hpp least_chi_square), not
  // the fit's own chi^2 (an upper bound of its least); always false where the criterion is not
  // noise-weighted.
  bool at_likelihood_maximum = false;
  int parameters = 0;  // its free parameters
  double wall_seconds = 0.0;
  std::string fitted;  // the added element's refitted values ("backlash.play.width = 0.91 mm, ..."); empty for the offset
  // Why the candidate cannot earn whatever it gains, or empty: a refitted resonance outside
  // the measured frequencies (candidate_model.hpp resolved_resonance).
  std::string unresolved;
  // Empty, or why this trial was refitted although not screened: the limit without inertia of
  // the candidate before it (a refitted slider-capped fluid column becomes the slider-capped
  // Maxwell element of its chamber and channel, which earns where the data hold no resonance
  // or cannot place it); the screen's simpler member of the effect (screen.hpp
  // ScreenedEffect::simpler); free play and a one-sided yield together (together.hpp).
  std::string limit_of;
  // With limit_of: the screen's best member of the effect, where it is not a slider-capped
  // fluid column (the reason names what was screened, then what was refitted instead or beside).
  std::string screened_as;
  bool chosen = false;  // the element added
};

struct Diagnosis {
  Verdict verdict = Verdict::none;
  Effect effect = Effect::none;  // the effect named; none for the verdicts none and unexplained
  std::string reason;            // why, with numbers
  // The verdict named: the other effects whose best refitted candidate earned too and fits
  // within DiagnoseSettings::parsimony of the named one's gap (evidence_text.hpp
  // alike_candidates): these data do not tell them apart from `effect`, which the rules of step
  // 4 chose (fewer parameters, else the lower BIC). Empty when the data tell them apart.
  std::vector<Effect> alike;
  ResidualPatterns patterns;  // of the model as fitted
  NoiseEstimate noise;        // behind the residual of the model as fitted, or at its least chi^2 where weighted
  double noise_ratio = 0.0;   // gap_before over the floor noise leaves (noise_estimate.hpp); 0 without an estimate
  // Where the criterion is noise-weighted: the least chi^2 of the model as fitted
  // (criterion.hpp least_chi_square) and sqrt(chi^2 / (N - p)), the residual at the likelihood's
  // maximum over the noise, which judges none against unexplained in place of noise_ratio.
  double chi_square_before = 0.0, chi_square_ratio = 0.0;
  std::optional<ResidualShape> unexplained;  // the verdict unexplained: where the residual lies, what it resembles
  FitResult before;
  std::optional<FitResult> after;            // the refined model refitted; empty for none
  std::string gap_name;                      // "err (6.1)" or "RMS force residual"
  double gap_before = 0.0, gap_after = 0.0;  // gap_after = gap_before for none
  int residual_terms = 0;                    // N of the criterion
  bool noise_weighted = false;               // the criterion is chi^2 under `noise` (criterion.hpp)
  double criterion_before = 0.0;
  std::vector<CandidateOutcome> candidates;  // every screened effect, screening order
  std::string added_element;                 // name in the refined model (`force_offset` for the effect offset); empty for none
  std::string added_summary;                 // what it is, with its fitted values
  std::vector<std::string> added_statement;  // its lines in the refined file (offset: the data lines, or the --data option)
  // The effect offset: the data sets (indices into the data) whose force offset the refined
  // model fits (`force_offset = free`; their fitted values in after->datasets); a later round
  // must read them so (rheo refine).
  std::vector<std::size_t> freed_offsets;
  std::string refined_text;   // the whole file with fitted values (and the element, with a comment)
  bool interrupted = false;   // a fit was stopped (Ctrl-C): the result so far
  bool time_limited = false;  // DiagnoseSettings::deadline cut a fit short or skipped one: the result so far
  // Own the models that before.network and after->network refer to.
  std::shared_ptr<const lang::Program> before_program, after_program;
};

// The solver diagnose() fits DATA by when its settings ask for ASKED. `auto` becomes fixed steps
// where DATA hold a time history: candidates that nest sliders and inerters would go to IDA,
// which restarts at every sample, where the fixed-step kernels take one exact step per sample.
// Harmonic tables alone keep `auto`: the candidates' closed forms and event-driven periodic
// states (numerics.md). Any other choice stands.
SolverChoice diagnosis_solver(SolverChoice asked, const std::vector<FitDataSet>& data);

// Throws what fit() throws, and lang::CompileError when SOURCE does not compile; std::logic_error
// (a bug of the caller) when SOURCE has no model SOURCE.model or SETTINGS.free names a parameter
// it does not have.
Diagnosis diagnose(const ModelSource& source, const std::vector<FitDataSet>& data, const DiagnoseSettings& settings);

// The gap of a fit as defined above.
double fit_gap(const FitResult& result);

// The verdict's word in reports and JSON: the effect's name, "none" or "unexplained".
std::string_view verdict_name(const Diagnosis& diagnosis);

}  // namespace rheo::runtime::diagnosis
