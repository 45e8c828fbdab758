// Shared helpers of the runtime tests: compile a model from source text, read tables.
#pragma once

#include "lang/frontend.hpp"
#include "runtime/io/fit_data.hpp"
#include "runtime/network/network.hpp"
#include "runtime/protocols/run_history.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <numbers>
#include <string>

namespace rheo::test {

// Whether this build runs under AddressSanitizer (CI's second build, RelWithDebInfo at -O1, each
// test several times slower): long loops over models or seeds run a shorter count there.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kUnderSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kUnderSanitizer = true;
#else
inline constexpr bool kUnderSanitizer = false;
#endif
#else
inline constexpr bool kUnderSanitizer = false;
#endif

inline lang::CheckedModel model_from(const std::string& source, const std::string& name) {
  const lang::Program program = lang::compile_source("test.rheo", source);
  const lang::CheckedModel* model = program.find_model(name);
  if (!model) throw std::runtime_error("test model not found: " + name);
  return *model;
}

inline runtime::Network network_from(const std::string& source, const std::string& name) {
  return runtime::Network::compile(model_from(source, name));
}

// The index of the model parameter at `path` ("m1.tau"), in Network::parameters() order.
inline int parameter_index(const runtime::Network& network, const std::string& path) {
  const auto& parameters = network.model().parameters;
  for (std::size_t i = 0; i < parameters.size(); ++i)
    if (parameters[i].path == path) return static_cast<int>(i);
  throw std::runtime_error("test model has no parameter " + path);
}

// A history data set whose force is the model's own response to `drive` (noise-free), plus a
// constant load-cell offset `offset` [N] (the data set declares none: see FitDataSet::force_offset).
inline runtime::FitDataSet history_data_of(const runtime::Network& truth, const runtime::Drive& drive, const std::string& path = "generated",
                                           double weight = 1.0, double offset = 0.0) {
  runtime::HistoryData h;
  h.path = path;
  h.drive = drive;
  h.force = runtime::run_history(truth, drive, false).force;
  for (double& f : h.force) f += offset;
  for (double f : h.force) h.force_scale = std::max(h.force_scale, std::abs(f));
  h.rows.assign(h.force.size(), 0);
  return {path, weight, h, {}};
}

// The whole content of a text file ("" when it cannot be read).
inline std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline double relative_error(double value, double reference) { return std::abs(value / reference - 1.0); }
inline double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }

// The Yeoh force-displacement law, eq. 3.3 written out term by term: F = 2 D10 u + 4 D20 u^3 +
// 6 D30 u^5 [N] for D10 [N/mm], D20 [N/mm^3], D30 [N/mm^5], u [mm]. The tests' own, so that a
// closed form built on it does not call runtime::YeohLaw, the code under test.
inline double yeoh_force(double d10, double d20, double d30, double u) {
  return 2.0 * d10 * u + 4.0 * d20 * std::pow(u, 3) + 6.0 * d30 * std::pow(u, 5);
}

}  // namespace rheo::test
