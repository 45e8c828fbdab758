#include "lang/names.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string_view>

namespace rheo::lang {

namespace {
// Levenshtein distance of A and B, or any value >= LIMIT once it is certain to reach LIMIT.
std::size_t edit_distance(std::string_view a, std::string_view b, std::size_t limit) {
  if ((a.size() > b.size() ? a.size() - b.size() : b.size() - a.size()) >= limit) return limit;
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    std::size_t smallest = row[0];
    for (std::size_t j = 1; j <= b.size(); ++j) {
      std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
      smallest = std::min(smallest, row[j]);
    }
    if (smallest >= limit) return limit;
  }
  return row[b.size()];
}

// Lists longer than this are shortened in messages.
constexpr std::size_t kListed = 30;
}  // namespace

std::string closest(std::string_view name, const std::vector<std::string>& candidates) {
  std::string best;
  if (candidates.size() > kMaxSuggestionCandidates) return best;
  std::size_t best_distance = std::max<std::size_t>(2, name.size() / 3) + 1;
  for (const auto& c : candidates) {
    std::size_t d = edit_distance(name, c, best_distance);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  return best;
}

std::string did_you_mean(std::string_view name, const std::vector<std::string>& candidates) {
  std::string best = closest(name, candidates);
  return best.empty() ? std::string() : fmt::format(" did you mean '{}'?", best);
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size() && i < kListed; ++i) out += (out.empty() ? "" : ", ") + items[i];
  if (items.size() > kListed) out += fmt::format(", ... ({} more)", items.size() - kListed);
  return out;
}

std::string join_chain(const std::vector<std::string>& names) {
  std::string out;
  const std::size_t head = kListed / 2, tail = kListed / 2;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names.size() > kListed && i == head) {
      out += fmt::format(" -> ... ({} more)", names.size() - head - tail);
      i = names.size() - tail;
    }
    out += (i == 0 ? "" : " -> ") + names[i];
  }
  return out;
}

std::string with_article(const Dimension& d) {
  std::string text = describe(d);
  if (d.dimensionless() || text.find('(') == std::string::npos) return text;
  return (std::string_view("aeio").find(text[0]) != std::string_view::npos ? "an " : "a ") + text;
}

std::string show_value(double internal_value, const Dimension& d, const std::string& unit) {
  if (auto u = parse_unit(unit); u && u->dimension == d) return fmt::format("{:g} {}", internal_value / u->scale, unit);
  std::string internal = internal_unit(d);
  return internal.empty() ? fmt::format("{:g}", internal_value) : fmt::format("{:g} {}", internal_value, internal);
}

}  // namespace rheo::lang
