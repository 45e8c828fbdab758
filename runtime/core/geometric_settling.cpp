#include "runtime/core/geometric_settling.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace rheo::runtime {

bool steady_contraction(double rate, double previous_rate) {
  const double spread = std::abs(rate - previous_rate);
  return rate >= 0.3 && rate <= 1.0 - 1e-7 && spread <= 0.05 * std::min(rate, 1.0 - rate);
}

ComponentSettling::ComponentSettling(std::vector<double> scales, double floor, double noise)
    : scales_(std::move(scales)), floor_(floor), noise_(std::min(noise, floor)), skipped_(scales_.size(), false), refused_(scales_.size(), false) {}

bool ComponentSettling::record(const std::vector<double>& state, std::vector<double>& target) {
  if (state.size() != scales_.size()) throw std::logic_error("ComponentSettling::record: a state of another size");
  if (kept_ == 4) std::rotate(std::begin(states_), std::begin(states_) + 1, std::end(states_)), kept_ = 3;
  states_[kept_++] = state;
  if (kept_ < 4) return false;
  target = state;
  bool moved = false;
  for (std::size_t i = 0; i < state.size(); ++i) {
    const double d0 = states_[1][i] - states_[0][i], d1 = states_[2][i] - states_[1][i], d2 = states_[3][i] - states_[2][i];
    skipped_[i] = false;
    if (refused_[i] || !(std::abs(d2) > noise_ * scales_[i]) || d0 == 0.0 || d1 == 0.0) continue;
    const double rate = d2 / d1, previous_rate = d1 / d0;
    if (!steady_contraction(rate, previous_rate)) continue;  // also excludes a change of sign
    const double remaining = d2 * rate / (1.0 - rate);
    if (!(std::abs(remaining) > floor_ * scales_[i])) continue;
    target[i] += remaining;
    skipped_[i] = true;
    moved = true;
  }
  return moved;
}

void ComponentSettling::refuse_last() {
  for (std::size_t i = 0; i < skipped_.size(); ++i)
    if (skipped_[i]) refused_[i] = true, skipped_[i] = false;
}

bool ComponentSettling::refused() const { return std::find(refused_.begin(), refused_.end(), true) != refused_.end(); }

}  // namespace rheo::runtime
