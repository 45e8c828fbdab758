// Wording helpers shared by the checker's messages.
#pragma once

#include "lang/units.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace rheo::lang {

// The candidate closest to NAME by edit distance, or "" when none is plausibly meant
// (distance > max(2, |NAME|/3)).
std::string closest(std::string_view name, const std::vector<std::string>& candidates);
// " did you mean 'x'?" or "".
std::string did_you_mean(std::string_view name, const std::vector<std::string>& candidates);
// "a, b, c"
std::string join(const std::vector<std::string>& items);
// "a stiffness (N/mm)", "an energy (N*mm)", "a plain number", "N/mm^3"
std::string with_article(const Dimension& d);
// A value in internal units shown in UNIT (when it parses) or in the internal unit: "-3 N/mm".
std::string show_value(double internal_value, const Dimension& d, const std::string& unit);

}  // namespace rheo::lang
