// libFuzzer target: the input is a fit's measured-data file (runtime/io/fit_data.hpp), read by
// read_fit_data itself, which takes only a path: each input is written to an in-memory file of
// this process (memfd) and read back through /proc/self/fd, so nothing touches the disk.
//
// The data line's reading (a TRIOS step, a columns mapping, the specimen's geometry, an
// amplitude for a table without one, duplicates) comes from the input too: a first line
//   # reading: step = Amplitude sweep; columns = frequency = f, storage = E_stor; area = 40; height = 20; amplitude = 0.1 %
// is a comment to the readers and sets the reading here (area in mm^2, height and amplitude in
// mm, an amplitude ending in % a strain; duplicates = error or average). Settings the checker
// would refuse before a reader sees them (a number not positive and finite, an unknown role, a
// role named twice) are left out, as the front end leaves them out. Inputs without the line
// are read with the default reading, so the CSV seeds stay as they are.
#include "documented_errors.hpp"
#include "runtime/io/column_roles.hpp"
#include "runtime/io/fit_data.hpp"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>

namespace {

int scratch_fd() {
  static const int fd = memfd_create("rheo_fit_data_fuzz.csv", 0);
  if (fd < 0) {
    std::perror("rheo fuzz: memfd_create");
    std::abort();
  }
  return fd;
}

std::string trimmed(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return "";
  return std::string(s.substr(first, s.find_last_not_of(" \t\r") - first + 1));
}

// A positive, finite number at the start of TEXT (the rest, e.g. "%", in REST).
std::optional<double> positive_number(const std::string& text, std::string& rest) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || !std::isfinite(value) || !(value > 0.0)) return std::nullopt;
  rest = trimmed(end);
  return value;
}

// `role = name, role = name`: each known role once, as check_columns (lang/fit_schema.cpp) passes it.
void add_columns(const std::string& text, rheo::runtime::ColumnReading& columns) {
  std::size_t start = 0;
  while (start <= text.size()) {
    auto comma = text.find(',', start);
    if (comma == std::string::npos) comma = text.size();
    const std::string pair = text.substr(start, comma - start);
    start = comma + 1;
    const auto equals = pair.find('=');
    if (equals == std::string::npos) continue;
    const std::string name = trimmed(std::string_view(pair).substr(equals + 1));
    const auto role = rheo::runtime::role_named(trimmed(std::string_view(pair).substr(0, equals)));
    if (!role || name.empty()) continue;
    if (std::any_of(columns.columns.begin(), columns.columns.end(), [&](const auto& c) { return c.first == *role; })) continue;
    columns.columns.emplace_back(*role, name);
  }
}

rheo::runtime::DataReading reading_from(std::string_view input) {
  rheo::runtime::DataReading reading;
  constexpr std::string_view marker = "# reading:";
  if (!input.starts_with(marker)) return reading;
  const std::string_view line = input.substr(marker.size(), input.find('\n') - marker.size());
  std::size_t start = 0;
  while (start <= line.size()) {
    auto semicolon = line.find(';', start);
    if (semicolon == std::string_view::npos) semicolon = line.size();
    const std::string_view setting = line.substr(start, semicolon - start);
    start = semicolon + 1;
    const auto equals = setting.find('=');
    if (equals == std::string_view::npos) continue;
    const std::string key = trimmed(setting.substr(0, equals)), value = trimmed(setting.substr(equals + 1));
    std::string rest;
    if (key == "step" && !value.empty()) reading.step = value;
    else if (key == "columns") add_columns(value, reading.columns);
    else if (key == "duplicates") reading.duplicates = value == "error" ? rheo::lang::DuplicatePoints::error : rheo::lang::DuplicatePoints::average;
    else if (const auto number = positive_number(value, rest)) {
      if (key == "area") reading.columns.area = *number;
      else if (key == "height") reading.columns.height = *number;
      else if (key == "amplitude" && rest == "%") reading.strain_amplitude = *number / 100.0;
      else if (key == "amplitude") reading.amplitude = *number;
    }
  }
  return reading;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const int fd = scratch_fd();
  if (ftruncate(fd, 0) != 0 || pwrite(fd, data, size, 0) != static_cast<ssize_t>(size)) {
    std::perror("rheo fuzz: cannot write the in-memory file");
    std::abort();
  }
  const std::string path = "/proc/self/fd/" + std::to_string(fd);
  const auto reading = reading_from(std::string_view(reinterpret_cast<const char*>(data), size));
  rheo::fuzz::expect_only_documented_errors([&] { (void)rheo::runtime::read_fit_data(path, 1.0, nullptr, reading); });
  return 0;
}
