// Force offsets of measured histories (FitDataSet::force_offset, a load cell's zero):
//   measured force m_j = network force p_j + c   [N].
// A declared c is added to the prediction wherever the data set is scored or drawn; the measured
// file is never altered. A free c enters a history's residuals r_j = s (p_j + c - m_j)
// (fit_scoring.hpp; s = sqrt(w / M) / max|m| is the same for all M samples of the file)
// affinely, so it is eliminated exactly at every evaluation (variable projection):
//   c* = argmin_c sum_j (p_j + c - m_j)^2 = mean_j (m_j - p_j).
// Every search and solve then sees the objective minimised over the offsets, with no unknown
// of its own; the separable fits stay exact, since p -> p + mean(m - p) is affine in p.
//
// Statistics: at the optimum the free offsets join the search coordinates z as linear
// coordinates, with the prediction's network part held, so the Jacobian is [J_z, J_c] with
// J_c's column for file f equal to s_f on f's samples and 0 elsewhere (differences of an affine
// map: exact). fit_statistics.hpp then gives the offsets' standard errors and correlations, and
// the parameters' standard errors account for the offsets (the residual variance counts them
// among the fitted unknowns).
#pragma once

#include "runtime/fit/fit_scoring.hpp"
#include "runtime/fit/fit_statistics.hpp"
#include "runtime/io/fit_data.hpp"

#include <cstddef>
#include <functional>
#include <limits>
#include <vector>

namespace rheo::runtime {

// The offset [N] that NETWORK_FORCE (the network's force at each sample of SET) is scored with
// under MODE; 0 for a harmonic table and where SET declares none.
double force_offset(const FitDataSet& set, const std::vector<double>& network_force, Offsets mode);

// A data set's force offset as fitted (DataSetFit::force_offset).
struct FittedOffset {
  bool given = false;  // written on the data line (harmonic tables: has no effect, not reported)
  bool free = false;
  double value = 0.0;                                                // N
  double standard_error = std::numeric_limits<double>::quiet_NaN();  // N; free only: +inf when not identifiable, NaN when not computed
  bool identifiable = true;
  std::vector<double> correlation{};  // free only: with each free parameter, in FitResult::free's order
};

struct StatisticsWithOffsets {
  ParameterStatistics parameters;     // the free parameters' (their coordinates first)
  std::vector<FittedOffset> offsets;  // per data set: standard_error, identifiable, correlation of free offsets
};

// FITTED's standard error, identifiability and correlations from STATISTICS (an entry of
// StatisticsWithOffsets::offsets).
void add_offset_statistics(FittedOffset& fitted, const FittedOffset& statistics);

// The statistics of a fit at search coordinates Z (LOGARITHMIC as in fit_statistics.hpp) with the
// free offsets of DATA as extra coordinates (see above). PREDICTIONS(z): every data set's
// prediction with Offsets::declared. Without free offsets this is parameter_statistics on the
// residuals. Throws what parameter_statistics throws.
// The statistics of the coordinates z (N of them) and, after them, the free offsets of the data
// sets FREE_SETS (indices into the fit's DATA_SETS data sets, in that order), split.
StatisticsWithOffsets split_offsets(const ParameterStatistics& all, std::size_t n, const std::vector<std::size_t>& free_sets, std::size_t data_sets);

StatisticsWithOffsets statistics_with_offsets(const std::function<std::vector<Prediction>(const std::vector<double>&)>& predictions,
                                              const std::vector<FitDataSet>& data, const ScoreSettings& score, const std::vector<double>& z,
                                              const std::vector<bool>& logarithmic);

}  // namespace rheo::runtime
