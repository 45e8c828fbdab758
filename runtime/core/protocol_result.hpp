// What a simulate protocol hands back: data, not text. The CLI renders it as CSV or JSON
// (output.hpp) and the report draws it (report/report_content.hpp).
// Units: amplitude, displacement and elongation mm; frequency Hz; force N; time s; stiffness
// N/mm; phase rad.
#pragma once

#include "runtime/core/drive.hpp"
#include "runtime/core/harmonic_point.hpp"

#include <string>
#include <variant>
#include <vector>

namespace rheo::runtime {

// What produced a result, for the comment line heading a file.
struct ResultHeader {
  std::string model;
  std::string source;    // the .rheo file
  std::string protocol;  // "harmonic steady_state=closed_form", "static velocity=0.05 mm/s cycles=2"
};

// The steady state at every point of a harmonic protocol's grid, characterised by `definition`.
struct HarmonicGrid {
  std::vector<HarmonicPoint> points;  // amplitudes outer, frequencies inner, as the protocol lists them
  HarmonicDefinition definition = HarmonicDefinition::thesis;
};

struct ProtocolResult {
  ResultHeader header;
  std::variant<HarmonicGrid, History> data;  // a grid from `harmonic`, a history from every other protocol
  int not_converged = 0;                     // harmonic points that did not reach steady state
  std::string notes;                         // warnings for standard error, one per line

  // Harmonic points or history samples.
  int size() const {
    if (const auto* grid = std::get_if<HarmonicGrid>(&data)) return static_cast<int>(grid->points.size());
    return static_cast<int>(std::get<History>(data).time.size());
  }
};

}  // namespace rheo::runtime
