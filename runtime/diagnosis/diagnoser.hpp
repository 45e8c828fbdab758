// The steps of one `rheo diagnose` (diagnose.hpp) as the methods of a Diagnoser: the model
// fitted and screened, the chosen candidate polished and written (diagnose.cpp); the candidates
// refitted (diagnose_refits.cpp); each judged, and the choice kept (diagnose_choice.cpp).
// Internal to runtime/diagnosis.
#pragma once

#include "lang/frontend.hpp"
#include "runtime/diagnosis/criterion.hpp"
#include "runtime/diagnosis/diagnose.hpp"
#include "runtime/diagnosis/offset_candidate.hpp"

#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace rheo::runtime::diagnosis {

struct Compiled {
  std::shared_ptr<const lang::Program> program;  // owns the model a Network refers to
  const lang::CheckedModel* model = nullptr;
};

// TEXT (the source of SOURCE.file, maybe edited) compiled, and its model SOURCE.model; a text
// without it is a bug.
Compiled compile(const ModelSource& source, const std::string& text);

struct Chosen {
  std::size_t candidate = 0;
  Trial trial;
  Compiled compiled;  // owns the model result.network refers to
  FitResult result;
  const std::vector<FitDataSet>* data = nullptr;  // as refitted: the offset candidate's frees force offsets
};

// One diagnosis, its steps as methods in the order of diagnose.hpp: fit the model (1), screen the
// effects (2), refit the leading ones and keep the one that earns (3, 4), polish it (5), and write
// the refined source.
class Diagnoser {
 public:
  Diagnoser(const ModelSource& source, const std::vector<FitDataSet>& data, const DiagnoseSettings& settings)
      : source_(source), data_(data), settings_(settings), s_(settings), base_(compile(source, source.text)) {
    s_.fit.score.method = FitMethod::exact;
    s_.fit.statistics = settings.standard_errors;
    s_.fit.score.harmonic.solver = diagnosis_solver(settings.fit.score.harmonic.solver, data);
  }

  Diagnosis run() {
    fit_model();
    refit_leading(screen_effects());
    if (!chosen_) refit_together();
    if (!chosen_) refit_as_written();
    if (!chosen_) return finish_none();
    polish();
    return finish_refined();
  }

 private:
  void stage(const std::string& what) const;

  // Seconds to the deadline; +inf without one.
  double time_left() const;

  // Whether the next step must not begin: a fit was interrupted, or the deadline has passed.
  bool stopped();

  // S with its fits bounded by SHARE of the time left (and by their own limit).
  DiagnoseSettings within(double share) const;

  std::vector<int> free_parameters() const;

  // Step 1: the model as given, fitted; its residual patterns and its fitted source.
  void fit_model();

  // Step 2: every effect screened, leading first.
  std::vector<ScreenedEffect> screen_effects();

  // The free parameters of a candidate model: those of step 1 it still has (kept, by path), and
  // the free parameters of its element ELEMENT (added).
  struct CandidateParameters {
    std::vector<int> kept, added;
  };
  CandidateParameters candidate_parameters(const lang::CheckedModel& candidate, const std::string& element) const;

  // Step 3: the leading effects refitted (a refitted capped fluid column is followed by its limit
  // without inertia, and where it stops short of the noise by itself with its walls' spring);
  // the others recorded as screened only.
  void refit_leading(const std::vector<ScreenedEffect>& screened_effects);

  // Of the refitted slider-capped Maxwell arms whose tau exceeds the longest the drives stick them
  // (candidate_model.hpp longest_stick), the one of the lowest gap, refitted as its limit tau ->
  // infinity, a friction element (candidate_model.hpp friction_limit): where the data cannot tell
  // the two apart, the friction element wins by parsimony. (Friction hidden in slow triangles was
  // named coupled: arms refitted to tau = 2.4e5 s and 8.4 s, sticking for at most 0.7 s, the
  // friction element itself screened fourth, 36.3 % against 36.4 %, and not refitted.)
  void refit_friction_limit();

  // RESULT, the refit of the capped Maxwell arm ELEMENT of MODEL over FREE, searched again where
  // the arm outlasts its sticking (candidate_model.hpp longest_stick) from each root friction
  // element's roles exchanged with the arm's (candidate_model.hpp roles_exchanged); the lower kept.
  void exchange_roles(const lang::CheckedModel& model, const std::string& element, const std::vector<int>& free, double share, FitResult& result);

  // The screen's simpler member of the effect, which screened within the parsimony margin of its
  // best (screen.hpp ScreenedEffect::simpler), refitted beside it. (A capped fluid column's
  // simpler member, the capped Maxwell element, is its limit without inertia, refitted anyway.)
  void refit_simpler(const ScreenedEffect& screened, double share);

  // The column's limit without inertia competes with it: where the data hold no resonance (or
  // cannot place it) the limit earns the coupling with one parameter fewer. Where the column
  // stops above its limit, it is searched again from the limit's optimum; BULGED becomes that
  // search's walls' start where it ends lower than the column at COLUMN_AT.
  void refit_limit(const ScreenedEffect& screened, const CandidateOutcome& outcome, const Trial& trial, const Trial& limit, std::size_t column_at,
                   double share, std::optional<Trial>& bulged);

  // Whether the column refitted at COLUMN_AT (or the search again after it, the last candidate
  // where that ended lower) leaves no more than the noise, as judge() counts reaching it.
  bool column_reaches_noise(std::size_t column_at) const;

  // BIC's parameter penalty p ln N of OUTCOME, and whether OUTCOME (its criterion less that
  // penalty the chi^2) reaches the noise as the verdict judges it (criterion.hpp reaches_noise).
  double penalty(const CandidateOutcome& outcome) const { return outcome.parameters * std::log(static_cast<double>(d_.residual_terms)); }
  bool outcome_reaches_noise(const CandidateOutcome& outcome) const;

  // Step 4 again where no candidate earned alone but both free play and asymmetry were
  // refitted: free play in front of a friction element whose yield is made one-sided, refitted
  // together (a friction branch behind play with unequal caps: each alone leaves the other's
  // residual). The element: the one the asymmetry was found in, else the root friction
  // element with the largest cap; the play's width and centre start from the best refitted
  // play, the split from the best refitted asymmetry (0.2 where it had none). Named by the
  // effect that did better alone.
  void refit_together();

  // Step 4 once more where no candidate earned and the residual is beyond the noise: the
  // leading refitted shapes (one per shape, lowest gap first, at most `confirm`) fitted as the
  // model was in step 1, every free parameter by rheo fit's strategy from the file's start
  // values with the element as screened, not from the model's fit: that fit may have taken the
  // missing effect into the model's own elements (a Maxwell element's tau at 132 ms for 7 ms, a
  // friction element's k at 950 N/mm for 114, where a capped Maxwell arm was missing), which no
  // local search from it gives back.
  void refit_as_written();

  // Whether the model's residual as fitted is beyond the estimated noise (unexplained, not none).
  bool residual_beyond_noise() const;

  // The name of TRIAL's element in the candidate model: a new root name (`backlash` for the
  // block that puts play in front of an element, also when refitted together with its
  // one-sided yield), or the element it replaces in place (a yeoh or poly_spring for a spring,
  // a friction element made one-sided).
  std::string element_name(const Trial& trial, Effect effect) const;

  // Steps 3 and 4 for one candidate: the fitted model with TRIAL added as OUTCOME.element,
  // refitted in two stages; recorded, and kept as the choice if it earns its parameters and is
  // preferred to the choice so far. Returns the limit without inertia of a capped fluid column,
  // and for the limit of COLUMN (given) that column started from the limit's optimum.
  // SHARE: of the time left, for this refit.
  // BULGED, where given, receives a refitted capped column's start with its walls' spring.
  std::optional<Trial> refit_candidate(const Trial& trial, CandidateOutcome& outcome, double share, const Trial* column = nullptr,
                                       std::optional<Trial>* bulged = nullptr);

  // Step 4 for a refitted candidate (RESULT, refitted to DATA, of the model CANDIDATE owns):
  // recorded in OUTCOME, and kept as the choice if it earns its parameters and is preferred to
  // the choice so far.
  void judge(const Trial& trial, CandidateOutcome& outcome, double share, std::chrono::steady_clock::time_point started, Compiled candidate,
             FitResult result, const std::vector<FitDataSet>& data);

  // OUTCOME's criterion at its likelihood's maximum, searched from its fit RESULT to DATA.
  void at_likelihood_maximum(CandidateOutcome& outcome, const FitResult& result, const std::vector<FitDataSet>& data, double share);

  // Whether OUTCOME (its fit RESULT to DATA), which earns, is preferred to the choice so far: the
  // one with fewer parameters when its gap is within `parsimony` of the other's (the coupled
  // shapes hold friction and Maxwell elements as limits, so they always fit at least as well),
  // unless the other's BIC is decisively lower (criterion.hpp decisively_lower: free play that
  // engages at the largest amplitudes fits within the margin of a stiffening yeoh spring's gap
  // with a chi^2 half of the spring's); else the lower BIC. Where the criterion is weighted by
  // the noise, BICs are compared with both at their likelihood's maximum, as the model's own is
  // (criterion_before): eq. 5.1's damping terms at phases near the phase noise can leave one
  // refit's chi^2 far above its least and not another's (a friction element's refit at 307, a
  // capped Maxwell arm's at 120; their least 100 and 99, one parameter apart); and of two
  // whose gaps lie beyond the margin the richer wins only where its BIC is positively lower
  // (criterion.hpp positively_lower), else the simpler.
  bool preferred_to_choice(CandidateOutcome& outcome, const FitResult& result, const std::vector<FitDataSet>& data, double share);

  // The data with the force offsets the offset candidate frees (offset_candidate.hpp).
  const std::vector<FitDataSet>& offset_data();

  FitResult refit_offsets(double share) { return refit_with_offsets(d_.before, offset_data(), within(share)); }

  // The model's residual as fitted, its chi^2 the least (criterion.hpp Residual).
  Residual before_residual() const { return {d_.gap_before, d_.chi_square_before, fitted_parameters(d_.before)}; }

  // Step 5: Levenberg-Marquardt over every free parameter of the chosen model again (refit.hpp
  // local_search), kept when no worse; its gaps' centres written within their play
  // (candidate_model.hpp with_gaps_in_play).
  void polish();

  // No candidate earned: the model as fitted, its residual at the noise (none) or not (unexplained).
  Diagnosis finish_none();

  // The chosen candidate: the refined source (the same structure as the refitted candidate,
  // under the comment that says why) with its fitted values.
  Diagnosis finish_refined();

  // finish_refined for the offset candidate: the model's structure kept, `force_offset = free`
  // written on the data lines of the histories whose offset it fits (or, for data given
  // otherwise, the --data option that says so).
  Diagnosis finish_offset();

  const ModelSource& source_;
  const std::vector<FitDataSet>& data_;
  const DiagnoseSettings& settings_;
  DiagnoseSettings s_;  // settings_ with the method exact and the statistics asked for
  const Compiled base_;
  Diagnosis d_;
  std::string fitted_text_;              // the source with the values of step 1
  Compiled fitted_;                      // fitted_text_ compiled
  std::vector<std::string> kept_paths_;  // the free parameters of step 1, by path
  DataScales scales_;
  std::optional<Chosen> chosen_;
  // Where the criterion is noise-weighted: the refitted candidate of the lowest gap that was not
  // chosen and whose BIC is its refit's, kept for finish_none to take at its likelihood's maximum.
  std::optional<Chosen> closest_;
  std::optional<std::vector<FitDataSet>> offset_data_;  // offset_data()
  // Of the refitted slider-capped Maxwell arms slower than the drives stick them, the one of the
  // lowest gap, and its friction limit (refit_friction_limit).
  struct CappedArm {
    CandidateOutcome arm;
    Trial limit;
    double gap = 0.0;
    double tau = 0.0;    // [s]
    double stick = 0.0;  // [s]: candidate_model.hpp longest_stick at the arm's fy/k
  };
  std::optional<CappedArm> capped_arm_;
};

}  // namespace rheo::runtime::diagnosis
