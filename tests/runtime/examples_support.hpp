// Helpers of the example tests (examples_test.cpp, examples_fit_test.cpp): the rheo binary run
// on the files of examples/, and err (6.1) between two harmonic grids computed here, from the
// thesis' definition, independently of runtime/fit: the noise floor of a measured file is the
// err of its noise-free reference grid against it (examples/data/README.md: the same model,
// without the noise), which a fit of the true structure cannot be expected to beat by much.
#pragma once

#include "runtime/io/history_csv.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace rheo::test::examples {

namespace fs = std::filesystem;

inline fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / fmt::format("rheo-examples-{}", ::getpid());
  fs::create_directories(dir);
  return dir;
}

// `rheo ARGUMENTS` through the shell (redirections allowed); the exit code, -1 if it did not exit.
inline int rheo_run(const std::string& arguments) {
  const std::string command = fmt::format("{} {}", RHEO_BINARY, arguments);
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

inline std::string example(const std::string& name) { return fmt::format("{}/{}", RHEO_EXAMPLES_DIR, name); }
inline std::string data(const std::string& name) { return fmt::format("{}/{}", RHEO_DATA_DIR, name); }

inline nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// err (6.1) = sqrt(phi) / n, phi (5.1) = sum (K_m/K_d - 1)^2 + (sin d_m / sin d_d - 1)^2 over the
// n points of DATA, of the grid MODEL (same points in the same order; columns amplitude,
// frequency, stiffness, phase). A damping term whose measured phase is <= 0 is left out, as
// rheo does (runtime/fit/objective.hpp), the point still counted in n.
inline double grid_err(const std::string& model, const std::string& data_file) {
  const runtime::Table m = runtime::read_table(model), d = runtime::read_table(data_file);
  REQUIRE(m.rows.size() == d.rows.size());
  double phi = 0.0;
  for (std::size_t i = 0; i < d.rows.size(); ++i) {
    REQUIRE(std::abs(m.columns[0][i] - d.columns[0][i]) < 1e-9);
    REQUIRE(std::abs(m.columns[1][i] - d.columns[1][i]) < 1e-9);
    phi += std::pow(m.columns[2][i] / d.columns[2][i] - 1.0, 2);
    if (d.columns[3][i] > 0.0) phi += std::pow(std::sin(m.columns[3][i]) / std::sin(d.columns[3][i]) - 1.0, 2);
  }
  return std::sqrt(phi) / static_cast<double>(d.rows.size());
}

}  // namespace rheo::test::examples
