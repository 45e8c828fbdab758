#include "runtime/diagnosis/together.hpp"

#include "runtime/diagnosis/element_text.hpp"

#include <fmt/format.h>

#include <limits>

namespace rheo::runtime::diagnosis {

std::optional<CandidateOutcome> played_and_split(const std::vector<CandidateOutcome>& candidates, const Network& fitted) {
  const CandidateOutcome *played = nullptr, *split = nullptr;
  for (const CandidateOutcome& c : candidates) {
    if (!c.refitted) continue;
    const Shape shape = c.screened.trial.shape;
    if ((shape == Shape::gapped_element || shape == Shape::gapped_spring) && (!played || c.gap_after < played->gap_after)) played = &c;
    if ((shape == Shape::one_sided_element || shape == Shape::asymmetric_friction) && (!split || c.gap_after < split->gap_after)) split = &c;
  }
  if (!played || !split) return std::nullopt;
  const lang::Element* element = nullptr;
  double largest_cap = 0.0;
  for (const lang::Element& e : fitted.model().root.children) {
    if (e.kind != lang::ElementKind::friction || e.parameters.size() != 2) continue;  // one cap both ways
    const double cap = fitted.parameter(e.parameters[1]);
    if (e.name == split->screened.trial.replaces) largest_cap = std::numeric_limits<double>::infinity(), element = &e;
    if (cap > largest_cap) largest_cap = cap, element = &e;
  }
  if (element == nullptr) return std::nullopt;
  const double bias = split->screened.trial.bias != 0.0 ? split->screened.trial.bias : 0.2;
  const auto inner = element_text(fitted, *element, bias);
  if (!inner) return std::nullopt;
  const bool backlash_first = played->gap_after <= split->gap_after;
  CandidateOutcome both;
  both.screened = backlash_first ? played->screened : split->screened;
  Trial& trial = both.screened.trial;
  trial = Trial{};
  trial.effect = both.screened.effect, trial.shape = Shape::gapped_element;
  trial.slip = played->screened.trial.slip, trial.bias = played->screened.trial.bias;
  trial.replaces = element->name, trial.inner = joined(*inner);
  both.limit_of = fmt::format("free play in front of '{}' and its yield made one-sided, together: neither earned alone", element->name);
  const CandidateOutcome& first = *(backlash_first ? played : split);  // its screened gain is the effect's best member's
  both.screened_as = first.screened_as.empty() ? trial_summary(first.screened.trial) : first.screened_as;
  return both;
}

}  // namespace rheo::runtime::diagnosis
