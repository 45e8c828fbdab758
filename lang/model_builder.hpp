// Checks one model: names its elements, flattens instantiated models, resolves parameter
// expressions (dimensions, values, reference cycles) and checks values and bounds.
#pragma once

#include "lang/ast.hpp"
#include "lang/diagnostics.hpp"

#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace rheo::lang {

// What the checker knows about a parameter beyond model.hpp's Parameter.
struct ParameterMeta {
  bool positive = false;                                   // value must be > 0
  bool derived = false;                                    // generated (maxwell c from tau, friction fy from uy): not overridable
  std::string quantity;                                    // "stiffness"; empty for model-level `param`s
  std::string owner_kind;                                  // "maxwell"; empty for model-level `param`s
  double below = std::numeric_limits<double>::infinity();  // value must be < below (springpot alpha < 1)
};

struct ModelInfo {
  CheckedModel model;
  std::vector<ParameterMeta> meta;  // parallel to model.parameters
  bool ok = true;                   // no error was reported for it
};

// The checked model an instantiation `NAME inst (...)` refers to, or nullptr when there is none
// usable (the lookup reports unknown names and recursion itself).
using ModelLookup = std::function<const ModelInfo*(const ast::Element& instance)>;

ModelInfo build_model(const ast::Model& model, const ModelLookup& lookup, std::vector<Diagnostic>& errors);

}  // namespace rheo::lang
