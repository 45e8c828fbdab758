// `--data`, shared by fit, report, diagnose and refine: a data file, or a data file with a data
// line's settings (`--data 'sweep.txt, step = "Amplitude sweep", area = 314 mm^2'`).
#pragma once

#include "runtime/io/fit_data.hpp"

#include <string>

namespace rheo::cli {

// What every --data help text says after its first sentence.
inline constexpr const char* data_option_settings_help =
    "FILE, or 'FILE, KEY = VALUE, ...' with a data line's settings (weight, columns, step, area, height, amplitude, duplicates), "
    "e.g. --data 'sweep.txt, step = \"Amplitude sweep\", columns = \"frequency = f\"'";

// The data set TEXT names, read as its settings ask (lang::parse_data_option), relative to the
// working directory. A setting that does not check is a UsageError naming --data; the file's
// own problems are DataErrors as for a data line.
runtime::FitDataSet read_data_option(const std::string& text);

}  // namespace rheo::cli
