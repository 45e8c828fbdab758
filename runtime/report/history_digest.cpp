#include "runtime/report/history_digest.hpp"

namespace rheo::runtime::report {

HistoryDigest::HistoryDigest() {
  displacement_.reserve(kCapacity + 1);  // no allocation while samples arrive
  force_.reserve(kCapacity + 1);
}

void HistoryDigest::begin(const ResultHeader&, const std::vector<std::string>&) { restart(); }

void HistoryDigest::write(const History& piece) {
  for (std::size_t k = 0; k < piece.time.size(); ++k, ++seen_) {
    if ((seen_ & (stride_ - 1)) != 0) continue;  // stride_ is a power of two
    displacement_.push_back(piece.displacement[k]);
    force_.push_back(piece.force[k]);
    if (displacement_.size() <= kCapacity) continue;
    // Kept entry 2i is sample 2i stride_: keep those, the stride doubled.
    for (std::size_t i = 0; 2 * i < displacement_.size(); ++i) displacement_[i] = displacement_[2 * i], force_[i] = force_[2 * i];
    const std::size_t kept = (displacement_.size() + 1) / 2;
    displacement_.resize(kept), force_.resize(kept);
    stride_ *= 2;
  }
}

void HistoryDigest::restart() {
  displacement_.clear(), force_.clear();
  seen_ = 0, stride_ = 1;
}

HistoryComparison HistoryDigest::comparison(const std::string& label) const {
  HistoryComparison h;
  h.label = label;
  h.displacement = displacement_;
  h.model_force = force_;
  return h;
}

}  // namespace rheo::runtime::report
