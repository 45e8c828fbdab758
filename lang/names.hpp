// Wording helpers shared by the checker's messages.
#pragma once

#include "lang/units.hpp"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace rheo::lang {

// Suggestions are made among at most this many candidates, so that a flood of misspelt names
// costs time in proportion to its size.
inline constexpr std::size_t kMaxSuggestionCandidates = 1000;

// The candidate closest to NAME by edit distance, or "" when none is plausibly meant
// (distance > max(2, |NAME|/3)) or there are more than kMaxSuggestionCandidates.
std::string closest(std::string_view name, const std::vector<std::string>& candidates);
// " did you mean 'x'?" or "".
std::string did_you_mean(std::string_view name, const std::vector<std::string>& candidates);
// "a, b, c"; past 30 items "a, b, ..., ... (N more)".
std::string join(const std::vector<std::string>& items);
// "a -> b -> c"; past 30 names the middle ones are left out: "a -> b -> ... (N more) -> y -> z".
std::string join_chain(const std::vector<std::string>& names);
// "a stiffness (N/mm)", "an energy (N*mm)", "a plain number", "N/mm^3"
std::string with_article(const Dimension& d);
// A value in internal units shown in UNIT (when it parses) or in the internal unit: "-3 N/mm".
std::string show_value(double internal_value, const Dimension& d, const std::string& unit);

}  // namespace rheo::lang
