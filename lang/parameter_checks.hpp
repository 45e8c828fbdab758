// Wording and value checks of one model parameter, for the model builder (model_builder.hpp).
#pragma once

#include "lang/ast.hpp"
#include "lang/diagnostics.hpp"
#include "lang/model_builder.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace rheo::lang {

// "maxwell 'm1'"
std::string describe_element(std::string_view kind, const std::string& path);
// "k of maxwell 'm1'", or "parameter 'k0'" for a model-level `param`.
std::string describe_parameter(const Parameter& p, const ParameterMeta& meta);

// P's evaluated value is finite, and positive when META requires it.
bool check_value(const Parameter& p, const ParameterMeta& meta, std::vector<Diagnostic>& errors);

// `in [LO, HI]` on P (evaluated): constant bounds of P's dimension (plain numbers in the unit of
// P's value), LO < HI, LO > 0 for positive parameters, and P's value within them. On success P
// becomes free with these bounds, in internal units.
bool check_bounds(Parameter& p, const ParameterMeta& meta, const ast::Bounds& bounds, std::vector<Diagnostic>& errors);

}  // namespace rheo::lang
