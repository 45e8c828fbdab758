// What the block-at-a-time history computations of the fit share (history_scoring.cpp,
// history_jacobian.cpp): several networks simulated in lockstep over a measured history, and the
// weights of its residuals (fit_scoring.hpp).
#pragma once

#include "runtime/core/parallel_for.hpp"
#include "runtime/io/fit_data.hpp"
#include "runtime/protocols/run_history.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <stdexcept>
#include <vector>

namespace rheo::runtime::history_blocks {

constexpr Eigen::Index kBlock = 1024;  // samples simulated per network before their rows are formed

// The forces of NETWORKS over H's drive in lockstep, a block at a time:
// visit(first, count, forces), forces(i, k) the force [N] of network k at sample first + i.
// Each block's networks are advanced side by side on up to THREADS threads (parallel_for.hpp;
// each stream its own state, so the forces do not depend on THREADS).
template <class Visit>
void for_each_block(const std::vector<Network>& networks, const HistoryData& h, SolverChoice solver, int threads, Visit&& visit) {
  std::vector<HistoryForceStream> streams;
  streams.reserve(networks.size());
  for (const Network& network : networks) streams.emplace_back(network, h.drive, solver);
  Eigen::MatrixXd forces(kBlock, static_cast<Eigen::Index>(networks.size()));
  std::vector<std::size_t> counts(streams.size());
  for (std::size_t first = 0; first < h.force.size();) {
    parallel_for(streams.size(), threads, [&](std::size_t k) {
      counts[k] = streams[k].next(std::span<double>(forces.col(static_cast<Eigen::Index>(k)).data(), static_cast<std::size_t>(kBlock)));
    });
    const std::size_t count = counts.empty() ? 0 : counts.front();
    if (count == 0 || std::any_of(counts.begin(), counts.end(), [&](std::size_t c) { return c != count; }))
      throw std::logic_error("for_each_block: the drive has fewer samples than the measured force");
    visit(first, count, forces);
    first += count;
  }
}

// sqrt(w / M) / max|F_exp|: the weight of one of SET's residuals (fit_scoring.hpp).
inline double residual_scale(const FitDataSet& set) {
  return std::sqrt(set.weight / static_cast<double>(set.history().force.size())) / set.history().force_scale;
}

inline bool free_offset(const FitDataSet& set) { return set.force_offset.given && set.force_offset.free; }

}  // namespace rheo::runtime::history_blocks
