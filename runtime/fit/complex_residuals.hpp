// The residual terms of a harmonic data set (append_residuals, fit_scoring.hpp) from complex
// model stiffnesses K*_j = K'_j + i K''_j [N/mm], for searches that form K* directly rather than
// simulate it (the diagnosis screen adds an element's K* to the fitted model's, thousands of
// times a screen). For a point of stiffness |K*| and phase arg K*:
//   eq. 5.1 (phi):  sign(K') |K*| / K_exp,signed - 1  and  (K''/|K*|) / sin(phase_exp) - 1,
// as sin(arg K*) = K''/|K*| and cos(arg K*) < 0 where K' < 0 (stiffness_residual's sign);
//   least squares:  (K* - K_exp e^{i phase_exp}) / K_exp.
// So no angle is formed from K*, and the measured side is formed once.
#pragma once

#include "runtime/fit/fit_scoring.hpp"

#include <complex>
#include <vector>

namespace rheo::runtime {

class ComplexResiduals {
 public:
  // SET must be harmonic; its weights and SCORE's objective and term weights are those
  // append_residuals applies.
  ComplexResiduals(const FitDataSet& set, const ScoreSettings& score);

  // OUT = the 2 n terms (point j's at 2j and 2j + 1) for K*_j = MODEL[j] + SHIFT [N/mm] (SHIFT a
  // stiffness added at every point, real); returns their sum of squares. MODEL holds n values.
  double terms(const std::vector<std::complex<double>>& model, double shift, std::vector<double>& out) const;

 private:
  struct Point {
    double stiffness_scale = 0.0;     // the point's scale times sqrt(w_K)
    double damping_scale = 0.0;       // times sqrt(w_d); 0 where the measured phase leaves the term out
    double signed_measured = 1.0;     // K_exp signed by its storage part [N/mm]
    double measured_sine = 1.0;       // sin(phase_exp)
    std::complex<double> measured;    // K_exp e^{i phase_exp} [N/mm]
    double measured_stiffness = 1.0;  // K_exp [N/mm], the least-squares terms' divisor
  };
  bool phi_;
  std::vector<Point> points_;
};

}  // namespace rheo::runtime
