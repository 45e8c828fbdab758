// Screening: which element, added to the fitted model, would explain most of the residual.
//
// For each effect, a family of trial elements (trial.hpp) spread over the measurement (times
// 1/(2 pi f) over the measured frequencies, slips over the measured amplitudes, resonances over
// the frequencies) is simulated alone at unit stiffness on every data point: its complex
// stiffness K*_c = K e^{i phase} per harmonic point, its force s(t) along each measured
// history. Added in parallel with size a (its force scales with a), the model would give
//   harmonic   K*_m + a K*_c + beta   (first-harmonic superposition; exact for linear elements)
//   history    F_m + a s(t) + beta u(t)
// (beta: the refit of the linear stiffness; added_objective.hpp) and the fit objective
// (fit_scoring.hpp) J(a) is minimised over a >= 0 (a log scan, then a golden section; a spring
// behind play over the stiffness it adds where it engages most, not over its k). A yeoh spring in place of the root spring adds 4 D20 a^2 + 6 D30 a^4 to the
// stiffness at amplitude a (4 D20 u^3 + 6 D30 u^5 to the force), minimised over D20 and D30.
// A trial that rebuilds a root element e of the model (free play in front of it, its one-cap
// yields split; element_text.hpp) replaces e's response s_e by its own s_p: F_m - s_e + a s_p,
// minimised over a in [0.1, 10] (s_p and s_e simulated alone at the fitted values).
// A force offset (offset_candidate.hpp) adds a constant c to the force of every history whose
// offset is not fitted already, c minimised over +-max|F_exp| (harmonic measures do not see it).
// gain = 1 - J(best)/J(0): the share of the objective the element would remove without any
// other parameter moving; a cheap, optimistic-or-pessimistic proxy for the refit that
// diagnose.hpp then does for the leading effects.
#pragma once

#include "runtime/diagnosis/trial.hpp"
#include "runtime/fit/fit.hpp"

#include <optional>
#include <vector>

namespace rheo::runtime::diagnosis {

// Where the measurement lies: the ranges the trial families are spread over.
struct DataScales {
  double frequency_low = 1.0, frequency_high = 1.0;  // [Hz]: measured, or a history's rates
  double amplitude_low = 1.0, amplitude_high = 1.0;  // [mm]: measured amplitudes, or a history's turning points
  BoundScales bounds;                                // typical stiffness and largest displacement
  bool has_history = false;                          // some data set is a history
  int fixed_offsets = 0;                             // histories whose force offset is not fitted (none, or declared)
  // Every data set is harmonic about zero displacement (no history, no preload). An element and
  // its mirror image (F(u) -> -F(-u): play centred at -c for +c) then score alike: the mirror's
  // periodic force under u0 sin(w t) is -F(t + T/2), which has the same max F - min F, loop
  // energy and first harmonic, so only one of the two is screened.
  bool symmetric_drives = false;
};

DataScales data_scales(const std::vector<FitDataSet>& data);

struct ScreenedEffect {
  Effect effect = Effect::none;
  Trial trial;        // the family member with the largest gain, sized by its best a (stiffness)
  double gain = 0.0;  // share of the objective it removes, in [0, 1]
  int trials = 0;     // family members simulated
  // The member of the shape that adds the fewest parameters (added_parameter_count), fewer than
  // `trial`, of those the best, where the objective it leaves is within (1 + parsimony)^2 of
  // what `trial` leaves, and its own gain: a gap
  // within the verdict's parsimony margin, closer than the screen's one-factor sizing (the
  // model's own elements held) can rank them. Refitted beside `trial` (diagnose.hpp step 3), so
  // that the verdict's parsimony has both to choose from: the yield forces of the model's own
  // friction element made one-sided (1 parameter) screened within 0.2 % of an added one-sided
  // friction element (3).
  std::optional<Trial> simpler;
  double simpler_gain = 0.0;
};

// FIT: the model fitted to DATA. Effects the model cannot take (a yeoh spring where the root
// already has one) or the data cannot show (asymmetry without a history: harmonic measures see
// only a law's odd part and a yield force's mean) are left out; the others are sorted by gain, largest first.
// PARSIMONY: DiagnoseSettings::parsimony, for ScreenedEffect::simpler.
std::vector<ScreenedEffect> screen(const FitResult& fit, const std::vector<FitDataSet>& data, const ScoreSettings& score, double parsimony);

// The trials of EFFECT over SCALES at unit stiffness (the yeoh one is sized by screen()).
// ROOT_SPRING names the root spring a yeoh replaces ("" when it is added).
std::vector<Trial> trial_family(Effect effect, const DataScales& scales, const std::string& root_spring);

}  // namespace rheo::runtime::diagnosis
