// The candidate rheo diagnose refits where none earned alone but free play and asymmetry were
// both refitted (diagnose.hpp, step 4): free play in front of a friction element whose yield is
// made one-sided, as one candidate. A friction branch behind play with unequal caps leaves, with
// either alone, the other's residual.
#pragma once

#include "runtime/diagnosis/diagnose.hpp"

#include <optional>
#include <vector>

namespace rheo::runtime::diagnosis {

// From the best refitted play (gapped_element, gapped_spring) and the best refitted asymmetry
// (one_sided_element, asymmetric_friction) of CANDIDATES: the gapped_element trial around the
// friction element the asymmetry was found in, else FITTED's root friction element (one cap both
// ways) with the largest cap, rewritten with its caps split by the asymmetry's bias (0.2 where it
// had none), the play's width and centre from the best play. Named by the effect that did better
// alone, `limit_of` saying why it is tried; `element` is left to the caller. nullopt where either
// is missing or FITTED has no such friction element.
std::optional<CandidateOutcome> played_and_split(const std::vector<CandidateOutcome>& candidates, const Network& fitted);

}  // namespace rheo::runtime::diagnosis
