// The variables of an exported FMU (docs/cli.md#rheo-export), shared by the modelDescription.xml
// that `rheo export` writes and the FMU binary that serves them, so that both number them alike:
//   value reference 0  u  input  [mm]  the terminal displacement (the other terminal is ground)
//   value reference 1  F  output [N]   the terminal force at the last communication point
//   value reference 2  v  input [mm/s] the terminal's velocity over the next step, for hosts that
//                                      provide it (0, its start: the input u is held); declared
//                                      u's time derivative (the `derivative` attribute, which both
//                                      standards offer for an input that is the derivative of
//                                      another: FMI 2.0 section 2.2.7, FMI 3.0 section 2.4.7.5)
//   value reference 3 + i              the model's parameter i (CheckedModel::parameters order),
//                                      in rheo's internal units (N, mm, s): a literal value is a
//                                      parameter the host may set until initialisation ends
//                                      (variability "fixed"), one computed from others (maxwell c
//                                      from tau, `k = 2 * k0`) a calculatedParameter.
//   value reference 3 + n  time [s]        the independent variable: the last communication point
//                                          (n parameters; declared in FMI 3.0's description, where
//                                          one variable must be independent; FMI 2.0 leaves it
//                                          implicit)
#pragma once

#include "lang/model.hpp"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rheo::runtime::fmu {

inline constexpr unsigned kInputU = 0;
inline constexpr unsigned kOutputF = 1;
inline constexpr unsigned kInputV = 2;
inline constexpr unsigned kFirstParameter = 3;

enum class Causality { input, output, parameter, calculated_parameter, independent };

struct Variable {
  std::string name;  // "u", "F", "v", or the parameter's path ("m1.tau")
  unsigned reference = 0;
  Causality causality = Causality::parameter;
  std::string unit;  // rheo's internal unit ("N/mm", "N*s/mm"); empty for a plain number
  double start = 0.0;
  // Bounds [internal units]: a parameter's `in [lo, hi]` when it has one, else the element
  // law's own (> 0: the least positive normal double; < 1: the largest double below 1); the
  // input's the range of a rig's displacement (lang/limits.hpp).
  std::optional<double> min, max;
  std::string description;
  int parameter = -1;                                    // index into CheckedModel::parameters; -1 for u, F, v and time
  std::optional<unsigned> derivative_of = std::nullopt;  // the value reference of the variable this one is the time derivative of (v: u)
};

// The variables of MODEL in value-reference order. ModelError when a model-level parameter is
// named `u`, `F`, `v` or `time`, the names of the FMU's inputs, output and independent variable.
std::vector<Variable> fmu_variables(const lang::CheckedModel& model);

// A fingerprint of what an FMU computes: rheo's version, the model's name and the source text,
// as the "{8-4-4-4-12}" hex form of a 128-bit hash (FNV-1a twice, different offsets). The FMU
// binary recomputes it from its resources and refuses a host that passes another.
std::string fmu_guid(std::string_view rheo_version, std::string_view model_name, std::string_view source);

}  // namespace rheo::runtime::fmu
