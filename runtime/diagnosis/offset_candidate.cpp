#include "runtime/diagnosis/offset_candidate.hpp"

#include "runtime/diagnosis/refit.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace rheo::runtime::diagnosis {
namespace {

// The byte offset of the start of the 1-based line LINE of TEXT (its end when it has fewer lines).
std::size_t line_start(const std::string& text, int line) {
  std::size_t at = 0;
  for (int k = 1; k < line; ++k) {
    const std::size_t newline = text.find('\n', at);
    if (newline == std::string::npos) return text.size();
    at = newline + 1;
  }
  return at;
}

}  // namespace

std::vector<std::size_t> fixed_offsets(const std::vector<FitDataSet>& data) {
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < data.size(); ++k)
    if (!data[k].is_harmonic() && !data[k].force_offset.free) out.push_back(k);
  return out;
}

std::vector<FitDataSet> with_free_offsets(const std::vector<FitDataSet>& data, const std::vector<std::size_t>& freed) {
  std::vector<FitDataSet> out = data;
  for (std::size_t k : freed) out[k].force_offset = ForceOffset{.given = true, .free = true, .value = 0.0};
  return out;
}

OffsetText offset_text(const std::string& text, const std::string& file, const std::vector<lang::FitData>& lines,
                       const std::vector<std::size_t>& freed, const FitResult& refit) {
  OffsetText out;
  for (std::size_t k : freed) {
    const DataSetFit& set = refit.datasets.at(k);
    out.summary += fmt::format("{}data {}: force_offset = {:.6g} N", out.summary.empty() ? "" : ", ", set.path, set.force_offset.value);
    const lang::FitData* line = k < lines.size() ? &lines[k] : nullptr;
    if (line == nullptr || line->where.file != file || line->end < 0 || static_cast<std::size_t>(line->end) > text.size() ||
        (line->force_offset.given && line->force_offset.value_begin < 0)) {
      out.statement.push_back(fmt::format("--data '{}, force_offset = free'", set.path));
      continue;
    }
    // A declared offset's value becomes `free`; a line without one gets the setting at its end.
    const lang::ForceOffsetSetting& given = line->force_offset;
    const bool declared = given.given && given.value_begin >= 0;
    const lang::FittedSetting edit = declared ? lang::FittedSetting{given.value_begin, given.value_end, "free"}
                                              : lang::FittedSetting{line->end, line->end, ", force_offset = free"};
    out.edits.push_back(edit);
    // The line as it will read, from the start of the line its file name is on to its end.
    const std::size_t first = line_start(text, line->where.line);
    std::string written = text.substr(first, static_cast<std::size_t>(line->end) - first);
    written.replace(static_cast<std::size_t>(edit.value_begin) - first, static_cast<std::size_t>(edit.value_end - edit.value_begin), edit.text);
    std::size_t from = 0;
    for (std::size_t next = 0; from <= written.size(); from = next + 1) {
      next = std::min(written.find('\n', from), written.size());
      std::string piece = written.substr(from, next - from);
      piece.erase(0, piece.find_first_not_of(" \t") == std::string::npos ? piece.size() : piece.find_first_not_of(" \t"));
      out.statement.push_back(piece);
    }
  }
  return out;
}

FitResult refit_with_offsets(const FitResult& before, const std::vector<FitDataSet>& freed_data, const DiagnoseSettings& settings) {
  const int n = static_cast<int>(before.free.size());
  const int evaluations = affordable_evaluations(before.network, freed_data, settings, kLocalJacobians * (n + 1));
  return fit(before.network, before.free, freed_data, local_search(settings.fit, evaluations));
}

std::vector<lang::FitData> fit_block_lines(const lang::Program& program, int block, std::size_t count) {
  if (block < 0 || static_cast<std::size_t>(block) >= program.fits.size()) return {};
  const std::vector<lang::FitData>& lines = program.fits[static_cast<std::size_t>(block)].data;
  return lines.size() == count ? lines : std::vector<lang::FitData>{};
}

std::vector<std::string> offset_header(const OffsetText& text, std::size_t freed, const std::string& gap_name, double before, double after) {
  std::vector<std::string> header{
      fmt::format("Refined by `rheo diagnose`: effect offset; {} {:.4g} -> {:.4g}; fitted {}.", gap_name, before, after, text.summary)};
  if (!text.edits.empty() && text.edits.size() == freed)
    header.emplace_back("force_offset = free is written on the data lines, so every fit of this file fits the offset.");
  else
    header.push_back(fmt::format("The data were not read from this file's data lines: give them as {} to fit the offset again.",
                                 fmt::join(text.statement, " ")));
  return header;
}

}  // namespace rheo::runtime::diagnosis
