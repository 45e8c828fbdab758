// `rheo fit FILE --orders maxwell=1..4,friction=1..6`: reads the counts, fits every structure of
// the model-order study (runtime/fit/order_study.hpp) and prints the table of err (6.1).
#include "lang/fitted_source.hpp"
#include "lang/frontend.hpp"
#include "cli/fit_job.hpp"
#include "cli/model_output.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/fit/order_study.hpp"
#include "runtime/io/output.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <memory>
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

// One fitted structure of the study: its program (which owns the model), fitted values and score.
struct FittedStructure {
  int maxwell = -1, friction = -1;
  std::string name, source;  // the name it was compiled under, and its text
  std::shared_ptr<const lang::Program> program;
  const lang::CheckedModel* model = nullptr;
  std::vector<int> free;
  std::vector<double> values;
  double err = 0.0, phi = 0.0;
};

// Start values for VARIANT from FROM's (e.g. --yeoh-start's; none: VARIANT's own), by parameter path.
std::vector<double> values_by_path(const lang::CheckedModel& variant, const lang::CheckedModel& from, const std::vector<double>& values) {
  if (values.empty()) return {};
  std::vector<double> out;
  for (const auto& p : variant.parameters) {
    out.push_back(p.value);
    for (std::size_t j = 0; j < from.parameters.size(); ++j)
      if (from.parameters[j].path == p.path && p.expression.is_constant()) out.back() = values[j];
  }
  return out;
}

// Akaike's criterion of a least-squares fit, N ln(phi/N) + 2 k, over N = 2 harmonic residuals
// per point (stiffness and phase): lower is better, err against the parameters spent on it.
double akaike(const FittedStructure& s, std::size_t points) {
  const double n = 2.0 * static_cast<double>(points);
  return n * std::log(std::max(s.phi, 1e-300) / n) + 2.0 * static_cast<double>(s.free.size());
}

// -o with --orders: the structure with the lowest Akaike criterion (lowest err without harmonic data).
void write_chosen(const std::vector<FittedStructure>& fitted, const FitJob& job, const std::string& path, const std::string& source_file) {
  std::size_t points = 0;
  for (const auto& set : job.data)
    if (set.is_harmonic()) points += set.harmonic().size();
  auto score = [&](const FittedStructure& s) { return points > 0 ? akaike(s, points) : s.err; };
  const FittedStructure& best = *std::min_element(fitted.begin(), fitted.end(), [&](const auto& a, const auto& b) { return score(a) < score(b); });
  auto count = [](int n) { return n < 0 ? std::string("as is") : std::to_string(n); };
  std::vector<std::string> header{
      fmt::format("Chosen by `rheo fit --orders` among {} structures: {} maxwell, {} friction elements,", fitted.size(), count(best.maxwell),
                  count(best.friction)),
      fmt::format("the lowest Akaike criterion N ln(phi/N) + 2 k (err (6.1) = {:.6g}, {} parameters).", best.err, best.free.size())};
  for (const auto& set : job.data) header.push_back(fmt::format("Data: {}", set.path));
  write_model_file(path, lang::write_fitted_source(best.source, best.name, *best.model, best.values, best.free, header), source_file);
  std::cerr << fmt::format("rheo: the chosen structure ({} maxwell, {} friction) written to {}\n", count(best.maxwell), count(best.friction), path);
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
  std::vector<FittedStructure> fitted;
  auto fitted_at = [&](int m, int f) -> const FittedStructure* {
    for (const auto& s : fitted)
      if (s.maxwell == m && s.friction == f) return &s;
    return nullptr;
  };
  for (const auto& [m, f, source] : study.variants()) {
    FittedStructure structure;
    structure.maxwell = m, structure.friction = f, structure.source = source;
    structure.name = fmt::format("<order study {}x{}>", m, f);
    structure.program = std::make_shared<const lang::Program>(lang::compile_source(structure.name, source));
    structure.model = structure.program->find_model(model.name);
    FitJob v = job;
    v.model = structure.model;
    v.free = lang::default_free_parameters(*v.model);
    // Warm from the structure with one friction (else one Maxwell) element fewer.
    const FittedStructure* previous = fitted_at(m, f - 1);
    if (previous == nullptr) previous = fitted_at(m - 1, f);
    v.start_values = previous ? study.warm_start(*v.model, *previous->model, previous->values) : values_by_path(*v.model, model, job.start_values);
    // The spread start too: the warm start's halves stay alike under a local search, where a
    // cold one may find a better use for the new element.
    if (previous) v.settings.extra_starts = {runtime::Network::compile(*v.model).parameters()};
    const runtime::FitResult r = run_fit_job(v);
    structure.free = r.free;
    structure.values = r.network.parameters();
    structure.err = r.err;
    structure.phi = r.phi;
    fitted.push_back(std::move(structure));
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
  // Only an explicit -o: the block's `output` names the file of the block's own fit.
  if (!options.output.empty()) write_chosen(fitted, job, options.output, options.file);
  if (options.json) std::cout << rows.dump(2) << "\n";
  return runtime::exit_code::ok;
}

}  // namespace rheo::cli
