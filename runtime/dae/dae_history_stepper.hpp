// A sampled drive through IDA one sample at a time (dae_integrator.hpp): what a history streamed
// from its file (protocols/stream_history.hpp) and a fit's history scored in blocks
// (protocols/run_history.hpp's HistoryForceStream) take, and what dae_history runs on a whole
// drive, so that all three give the same numbers bit for bit. It holds the last three samples
// and a look-ahead, not the drive: memory does not grow with the history's length.
//
// IDA's absolute tolerances and its restart horizon are set by the whole drive (its largest
// |u| and its duration, dae_protocols.hpp), so they are given up front: a streamed history reads
// its file once for them before it runs (DaeHistoryScales).
#pragma once

#include "runtime/core/drive.hpp"
#include "runtime/dae/dae_graph.hpp"
#include "runtime/dae/dae_integrator.hpp"
#include "runtime/network/network.hpp"

#include <cstddef>
#include <memory>
#include <vector>

namespace rheo::runtime {

// What IDA's settings for a history depend on: the drive's largest |u| [mm] and its duration,
// last time minus first [s]. Accumulated sample by sample (add), or of a whole drive (of).
struct DaeHistoryScales {
  double reach = 0.0, duration = 0.0;
  void add(double t, double u);
  static DaeHistoryScales of(const Drive& drive);

 private:
  double first_time_ = 0.0;
  bool started_ = false;
};

class DaeHistoryStepper {
 public:
  // ELEMENTS: also every element's force and elongation (Topology::probes order) per sample.
  // NETWORK must outlive the stepper.
  DaeHistoryStepper(const Network& network, bool elements, const DaeHistoryScales& scales);
  ~DaeHistoryStepper();
  DaeHistoryStepper(const DaeHistoryStepper&) = delete;
  DaeHistoryStepper& operator=(const DaeHistoryStepper&) = delete;

  // Sample 0 at time T0 [s] and displacement U0 [mm]: from rest (START null; U0 must then be 0),
  // or from START, the relaxed state at U0. Returns its force [N].
  double start(double t0, double u0, const StartAtRest* start = nullptr);
  // The next sample, at time T [s] (after the last) and displacement U [mm]; returns its force
  // [N], the left limit at T (docs/numerics.md, "Drives"). NumericalError where IDA fails.
  double step(double t, double u);

  // The last sample's element forces [N] and elongations [mm] (with ELEMENTS).
  const std::vector<double>& element_force() const { return element_force_; }
  const std::vector<double>& element_elongation() const { return element_elongation_; }
  DaeStatistics statistics() const { return integrator_->statistics(); }

 private:
  const Network& network_;
  DaeGraph graph_;  // before integrator_, which refers to it
  double duration_;
  std::unique_ptr<DaeIntegrator> integrator_;
  bool elements_;
  std::vector<double> positions_;  // the start's node positions [mm]; empty: from rest
  // The drive's last samples and a look-ahead one sample interval past the newest (so that the
  // newest is a stop of the integration, as every sample but the last is on a whole drive).
  Drive window_;
  std::size_t taken_ = 0;  // samples taken so far
  std::vector<double> element_force_, element_elongation_;
};

}  // namespace rheo::runtime
