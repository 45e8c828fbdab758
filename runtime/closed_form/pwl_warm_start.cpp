#include "runtime/closed_form/pwl_warm_start.hpp"

#include <algorithm>
#include <stdexcept>
#include <tuple>

namespace rheo::runtime {
namespace {

template <class A, class B>
bool key_less(const A& a, const B& b) {
  return std::tie(a.u0, a.omega, a.branch) < std::tie(b.u0, b.omega, b.branch);
}

struct Key {
  double u0, omega;
  int branch;
};

}  // namespace

void PwlWarmStarts::clear() {
  const std::lock_guard lock(mutex_);
  count_ = 0;
  sealed_ = false;
}

void PwlWarmStarts::record(double u0, double omega, int branch, const PwlStart& start) {
  const std::lock_guard lock(mutex_);
  if (sealed_) throw std::logic_error("PwlWarmStarts::record after seal");
  if (count_ == entries_.size()) entries_.emplace_back();
  Entry& e = entries_[count_++];
  e.u0 = u0, e.omega = omega, e.branch = branch;
  e.start.X0 = start.X0;
  e.start.mode.assign(start.mode.begin(), start.mode.end());
  e.start.allowed = start.allowed;
}

void PwlWarmStarts::seal() {
  const std::lock_guard lock(mutex_);
  if (sealed_) return;
  // Records of one key (repeated data points) hold the same bits: any order serves.
  std::sort(entries_.begin(), entries_.begin() + static_cast<std::ptrdiff_t>(count_), [](const Entry& a, const Entry& b) { return key_less(a, b); });
  sealed_ = true;
}

const PwlStart* PwlWarmStarts::find(double u0, double omega, int branch) const {
  if (!sealed_) return nullptr;
  const Key key{u0, omega, branch};
  const auto end = entries_.begin() + static_cast<std::ptrdiff_t>(count_);
  const auto it = std::lower_bound(entries_.begin(), end, key, [](const Entry& e, const Key& k) { return key_less(e, k); });
  if (it == end || it->u0 != u0 || it->omega != omega || it->branch != branch) return nullptr;
  return &it->start;
}

}  // namespace rheo::runtime
