// `rheo fit FILE --orders maxwell=1..4,friction=1..6`: reads the counts, fits every structure of
// the model-order study (runtime/fit/order_study.hpp) and prints the table of err (6.1).
#include "lang/frontend.hpp"
#include "cli/fit_job.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/fit/order_study.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <regex>

namespace rheo::cli {
namespace {

using runtime::CountRange;
using runtime::OrderSpec;

OrderSpec parse_orders(const std::string& text) {
  OrderSpec spec;
  const std::regex item(R"(\s*(maxwell|friction)\s*=\s*(\d+)\s*(?:\.\.\s*(\d+))?\s*)");
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::string part = text.substr(start, end - start);
    std::smatch m;
    if (!std::regex_match(part, m, item))
      throw runtime::UsageError(fmt::format("--orders: cannot read '{}'; write e.g. --orders maxwell=1..4,friction=1..6", part));
    CountRange r{std::stoi(m[2]), m[3].matched ? std::stoi(m[3]) : std::stoi(m[2])};
    if (r.last < r.first || r.last > 50)
      throw runtime::UsageError(fmt::format("--orders: '{}' is not a range of counts from low to high (at most 50)", part));
    (m[1] == "maxwell" ? spec.maxwell : spec.friction) = r;
    start = end + 1;
  }
  return spec;
}

}  // namespace

int run_order_study(const std::vector<FitJob>& jobs, const FitOptions& options) {
  if (jobs.size() != 1) throw runtime::UsageError("--orders studies one fit; select it with --model");
  const FitJob& job = jobs.front();
  const lang::CheckedModel& model = *job.model;
  const runtime::OrderStudy study(model, parse_orders(options.orders), job.data);
  nlohmann::json rows = nlohmann::json::array();
  if (!options.json)
    std::cout << fmt::format("model-order study of {} (method {}): err (6.1) on all harmonic data\n{:>10}  {:>10}  {:>10}  {:>12}  {:>8}\n",
                             model.name, job.description.method, "maxwell", "friction", "parameters", "err", "seconds");
  for (const auto& [m, f, source] : study.variants()) {
    const lang::Program variant = lang::compile_source(fmt::format("<order study {}x{}>", m, f), source);
    FitJob v = job;
    v.model = variant.find_model(model.name);
    v.free = lang::default_free_parameters(*v.model);
    const runtime::FitResult r = run_fit_job(v);
    rows.push_back({{"maxwell", std::max(m, 0)},
                    {"friction", std::max(f, 0)},
                    {"parameters", r.free.size()},
                    {"err", r.err},
                    {"phi", r.phi},
                    {"evaluations", r.evaluations},
                    {"wall_seconds", r.wall_seconds}});
    if (!options.json)
      std::cout << fmt::format("{:>10}  {:>10}  {:>10}  {:>12.4e}  {:>8.2f}\n", m < 0 ? std::string("as is") : std::to_string(m),
                               f < 0 ? std::string("as is") : std::to_string(f), r.free.size(), r.err, r.wall_seconds)
                << std::flush;
    if (r.interrupted) {
      if (options.json) std::cout << rows.dump(2) << "\n";
      return exit_code_interrupted;
    }
  }
  if (options.json) std::cout << rows.dump(2) << "\n";
  return runtime::exit_code::ok;
}

}  // namespace rheo::cli
