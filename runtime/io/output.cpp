#include "runtime/io/output.hpp"

#include "runtime/core/errors.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <numbers>

namespace rheo::runtime {
namespace {

constexpr double kDegree = 180.0 / std::numbers::pi;

std::string comment_lines(const ResultHeader& h) { return fmt::format("# rheo {}: model {} from {}\n", h.protocol, h.model, h.source); }

const char* definition_name(HarmonicDefinition d) { return d == HarmonicDefinition::thesis ? "thesis" : "first_harmonic"; }

// Significant digits for a column of VALUES: 6, or more where 6 would write two values that
// differ by more than a relative 1e-9 (apart as data points, docs/errors.md#csv-tables) alike,
// so that a result read back as measured data keeps its points apart; at most 17 (exact).
int column_digits(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  values.erase(
      std::unique(values.begin(), values.end(), [](double a, double b) { return std::abs(b - a) <= 1e-9 * std::max(std::abs(a), std::abs(b)); }),
      values.end());
  int digits = 6;
  for (std::size_t k = 1; k < values.size() && digits < 17; ++k)
    while (digits < 17 && fmt::format("{:.{}g}", values[k - 1], digits) == fmt::format("{:.{}g}", values[k], digits)) ++digits;
  return digits;
}

}  // namespace

std::string harmonic_csv(const ResultHeader& header, const std::vector<HarmonicPoint>& points, HarmonicDefinition definition) {
  std::string out = comment_lines(header);
  out += definition == HarmonicDefinition::thesis
             ? "# definition thesis: stiffness = (max F - min F)/(2 u0), phase = asin(U/(pi F^ u0)) (eqs. 1.2, 5.26, 5.27)\n"
             : "# definition first_harmonic: stiffness = |F1|/u0, phase = arg F1 of the first harmonic of the force\n";
  // A preload column only where a point has one: results without stay as they were.
  const bool preloaded = std::any_of(points.begin(), points.end(), [](const HarmonicPoint& p) { return p.preload != 0.0; });
  out +=
      "amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg],damping [-],storage [N/mm],loss [N/mm],"
      "force_amplitude [N],energy [N*mm],cycles [-],converged [-]";
  out += preloaded ? ",preload [mm]\n" : "\n";
  std::vector<double> amplitudes, frequencies;
  for (const auto& p : points) amplitudes.push_back(p.amplitude), frequencies.push_back(p.frequency);
  const int amplitude_digits = column_digits(amplitudes), frequency_digits = column_digits(frequencies);
  for (const auto& p : points) {
    const auto& m = p.measures;
    out += fmt::format("{:.{}g},{:.{}g},{:.10g},{:.8g},{:.8g},{:.10g},{:.10g},{:.10g},{:.10g},{},{}", p.amplitude, amplitude_digits, p.frequency,
                       frequency_digits, m.stiffness, m.phase * kDegree, m.damping, m.storage, m.loss, m.force_amplitude, m.energy, p.cycles,
                       p.converged ? 1 : 0);
    out += preloaded ? fmt::format(",{}\n", p.preload) : "\n";
  }
  return out;
}

std::string harmonic_json(const ResultHeader& header, const std::vector<HarmonicPoint>& points, HarmonicDefinition definition) {
  nlohmann::ordered_json j;
  j["model"] = header.model;
  j["source"] = header.source;
  j["protocol"] = "harmonic";
  j["definition"] = definition_name(definition);
  j["units"] = {{"amplitude", "mm"}, {"frequency", "Hz"}, {"stiffness", "N/mm"},    {"phase", "deg"},
                {"storage", "N/mm"}, {"loss", "N/mm"},    {"force_amplitude", "N"}, {"energy", "N*mm"}};
  if (std::any_of(points.begin(), points.end(), [](const HarmonicPoint& p) { return p.preload != 0.0; })) j["units"]["preload"] = "mm";
  auto& list = j["points"] = nlohmann::ordered_json::array();
  for (const auto& p : points) {
    const auto& m = p.measures;
    list.push_back({{"amplitude", p.amplitude},
                    {"frequency", p.frequency},
                    {"stiffness", m.stiffness},
                    {"phase", m.phase * kDegree},
                    {"damping", m.damping},
                    {"storage", m.storage},
                    {"loss", m.loss},
                    {"force_amplitude", m.force_amplitude},
                    {"energy", m.energy},
                    {"cycles", p.cycles},
                    {"converged", p.converged}});
    if (p.preload != 0.0) list.back()["preload"] = p.preload;
  }
  return j.dump(2) + "\n";
}

std::string history_csv_head(const ResultHeader& header, const std::vector<std::string>& element_paths) {
  std::string out = comment_lines(header);
  out += "time [s],displacement [mm],force [N]";
  for (const auto& path : element_paths) out += fmt::format(",{0}.force [N],{0}.elongation [mm]", path);
  out += "\n";
  return out;
}

namespace {

// V shortest-round-trip (fmt's "{}": Dragonbox; fixed notation for exponents -5 to 15) at P,
// then SEPARATOR; returns the end.
char* write_number(char* p, double v, char separator) {
  p = fmt::format_to(p, FMT_COMPILE("{}"), v);
  *p++ = separator;
  return p;
}

}  // namespace

std::size_t max_history_row_bytes(std::size_t elements) {
  return 25 * (3 + 2 * elements);  // at most 24 characters a number ("-2.2250738585072014e-308") and its separator
}

char* write_history_row(char* p, const History& h, std::size_t k) {
  const std::size_t elements = h.element_paths.size();
  p = write_number(p, h.time[k], ',');
  p = write_number(p, h.displacement[k], ',');
  p = write_number(p, h.force[k], elements ? ',' : '\n');
  for (std::size_t i = 0; i < elements; ++i) {
    p = write_number(p, h.element_force[i][k], ',');
    p = write_number(p, h.element_elongation[i][k], i + 1 < elements ? ',' : '\n');
  }
  return p;
}

void append_history_rows(std::string& out, const History& h) {
  const std::size_t widest = max_history_row_bytes(h.element_paths.size());
  std::vector<char> rows(std::max<std::size_t>(widest, 1 << 16));
  char* p = rows.data();
  for (std::size_t k = 0; k < h.time.size(); ++k) {
    if (static_cast<std::size_t>(rows.data() + rows.size() - p) < widest) {
      out.append(rows.data(), p);
      p = rows.data();
    }
    p = write_history_row(p, h, k);
  }
  out.append(rows.data(), p);
}

std::string history_csv(const ResultHeader& header, const History& h) {
  std::string out = history_csv_head(header, h.element_paths);
  append_history_rows(out, h);
  return out;
}

std::string rendered(const ProtocolResult& result, lang::OutputFormat format) {
  const bool json = format == lang::OutputFormat::json;
  if (const auto* grid = std::get_if<HarmonicGrid>(&result.data))
    return json ? harmonic_json(result.header, grid->points, grid->definition) : harmonic_csv(result.header, grid->points, grid->definition);
  const History& history = std::get<History>(result.data);
  return json ? history_json(result.header, history) : history_csv(result.header, history);
}

std::string history_json(const ResultHeader& header, const History& h) {
  nlohmann::ordered_json j;
  j["model"] = header.model;
  j["source"] = header.source;
  j["protocol"] = header.protocol;
  j["units"] = {{"time", "s"}, {"displacement", "mm"}, {"force", "N"}, {"elongation", "mm"}};
  j["time"] = h.time;
  j["displacement"] = h.displacement;
  j["force"] = h.force;
  auto& elements = j["elements"] = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < h.element_paths.size(); ++i)
    elements.push_back({{"path", h.element_paths[i]}, {"force", h.element_force[i]}, {"elongation", h.element_elongation[i]}});
  return j.dump() + "\n";
}

}  // namespace rheo::runtime
