// Writing fitted parameter values back into the source text a model was compiled from.
#pragma once

#include "lang/diagnostics.hpp"
#include "lang/model.hpp"

#include <string>
#include <vector>

namespace rheo::lang {

// Returns SOURCE (the text of FILE, as compiled into MODEL) with the value expression of every
// parameter listed in CHANGED replaced by its value in VALUES, written as format_parameter_value
// does. Bounds, comments, layout and everything else are kept byte for byte. HEADER lines (the
// vector may be empty) are put first as `# ` comment lines.
//   VALUES: indexed like MODEL.parameters (its size), internal units.
//   CHANGED: indices into MODEL.parameters (order and repetitions do not matter).
// Throws CompileError, located at the parameter, when a changed parameter's value is computed
// from other parameters or is not written for it in FILE (a stdlib default, an instantiated
// model's default): the message says to override it in the instantiation. Throws
// std::logic_error (a bug of the caller) when VALUES has the wrong size, an index is out of
// range, a value is not finite, or a range lies outside SOURCE (SOURCE is not the text MODEL was
// compiled from).
// SETTINGS: values of data-line settings to write too (`force_offset = free` becomes
// `force_offset = 123.4 N`), each replacing the byte range of its value in SOURCE; an empty
// range inserts its text there (`, force_offset = free` after a data line's last setting).
struct FittedSetting {
  int value_begin = -1, value_end = -1;  // [value_begin, value_end) in SOURCE; value_begin == value_end: an insertion
  std::string text;                      // the value written there
};
std::string write_fitted_source(const std::string& source, const std::string& file, const CheckedModel& model, const std::vector<double>& values,
                                const std::vector<int>& changed, const std::vector<std::string>& header,
                                const std::vector<FittedSetting>& settings = {});

// VALUE (internal units) as the value expression of P: in P's unit when it has one, else in
// the internal unit of P's dimension ("Hz" for frequencies; plain when dimensionless). The
// number has 10 significant digits, or the fewest more (up to 17) that compile back to VALUE
// within 1e-13 relative; trailing zeros are dropped ("101.58 um"). VALUE must be finite
// (std::logic_error otherwise).
std::string format_parameter_value(const Parameter& p, double value);

}  // namespace rheo::lang
