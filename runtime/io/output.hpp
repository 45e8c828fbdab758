// Result formats (files are written by output_file.hpp).
//
// Harmonic CSV: the first four columns are exactly
//   amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]
// (the format of the measured data, so a result can be fitted later), then
//   damping [-],storage [N/mm],loss [N/mm],force_amplitude [N],energy [N*mm],cycles [-],converged [-]
// History CSV: time [s],displacement [mm],force [N], then per element "PATH.force [N]" and
// "PATH.elongation [mm]", each number shortest-round-trip. '#' lines before the header say what
// produced the file.
#pragma once

#include "lang/protocol_settings.hpp"
#include "runtime/core/drive.hpp"
#include "runtime/core/harmonic_point.hpp"
#include "runtime/core/protocol_result.hpp"
#include "runtime/io/output_file.hpp"

#include <string>
#include <vector>

namespace rheo::runtime {

std::string harmonic_csv(const ResultHeader& header, const std::vector<HarmonicPoint>& points, HarmonicDefinition definition);
std::string harmonic_json(const ResultHeader& header, const std::vector<HarmonicPoint>& points, HarmonicDefinition definition);
std::string history_csv(const ResultHeader& header, const History& history);
// The parts of history_csv, for a history written piece by piece: the comment line and the
// names row, and the rows of PIECE appended to OUT. Numbers are written shortest-round-trip
// (fmt's "{}"): read back, each is the double that was written.
std::string history_csv_head(const ResultHeader& header, const std::vector<std::string>& element_paths);
void append_history_rows(std::string& out, const History& piece);
// Row K of H written at P, which must have room for max_history_row_bytes(H's elements);
// returns the end of the row (past its '\n').
std::size_t max_history_row_bytes(std::size_t elements);
char* write_history_row(char* p, const History& h, std::size_t k);
std::string history_json(const ResultHeader& header, const History& history);
// A protocol's result in FORMAT: one of the four above.
std::string rendered(const ProtocolResult& result, lang::OutputFormat format);

}  // namespace rheo::runtime
