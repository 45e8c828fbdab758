// `rheo fit FILE --orders maxwell=1..4,friction=1..6`: the model-order study of thesis Fig. 6.2.
//
// The model must hold only leaves in its root parallel block. For every combination of counts,
// its Maxwell and friction elements are replaced by that many copies of the first one (same
// bounds and units), with start values spread log-evenly over the data: relaxation times over
// 1/(2 pi f) for the measured frequencies, slip displacements over the measured amplitudes. The
// other elements keep their values and bounds. Each structure is written as .rheo source,
// compiled and fitted like the original; the table gives err (6.1) against the element counts.
#include "lang/fitted_source.hpp"
#include "lang/frontend.hpp"
#include "cli/fit_job.hpp"
#include "runtime/core/errors.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <regex>

namespace rheo::cli {
namespace {

struct CountRange {
  int first = 0, last = 0;
};

struct OrderSpec {
  std::optional<CountRange> maxwell, friction;
};

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

std::vector<double> log_spread(double lo, double hi, int count) {
  std::vector<double> v;
  for (int i = 0; i < count; ++i)
    v.push_back(count == 1 ? std::sqrt(lo * hi) : lo * std::pow(hi / lo, static_cast<double>(i) / (count - 1)));
  return v;
}

const lang::Parameter* parameter(const lang::CheckedModel& model, const std::string& path) {
  for (const auto& p : model.parameters)
    if (p.path == path) return &p;
  return nullptr;
}

std::string argument(const lang::Parameter& p, const std::string& name, double value) {
  std::string text = fmt::format("{} = {}", name, lang::format_parameter_value(p, value));
  if (p.free) {
    const double clamped = std::clamp(value, p.lower, p.upper);
    text = fmt::format("{} = {} in [{}, {}]", name, lang::format_parameter_value(p, clamped), lang::format_parameter_value(p, p.lower),
                       lang::format_parameter_value(p, p.upper));
  }
  return text;
}

// The written arguments of a leaf (generated ones, like c from tau, left out).
std::string arguments_of(const lang::CheckedModel& model, const lang::Element& e) {
  std::vector<std::string> args;
  for (const auto& p : model.parameters)
    if (p.path.starts_with(e.path + ".") && p.value_begin >= 0 && p.path.find('.', e.path.size() + 1) == std::string::npos)
      args.push_back(argument(p, p.path.substr(e.path.size() + 1), p.value));
  return fmt::format("{}", fmt::join(args, ", "));
}

struct Spreads {
  std::vector<double> tau, uy;  // s, mm
};

// The copies of `templ` (a maxwell or friction leaf), as source lines.
std::string copies(const lang::CheckedModel& model, const lang::Element& templ, int count, const Spreads& spreads) {
  const bool is_maxwell = templ.kind == lang::ElementKind::maxwell;
  const lang::Parameter* k = parameter(model, templ.path + ".k");
  const lang::Parameter* tau = parameter(model, templ.path + (is_maxwell ? ".tau" : ".uy"));
  const lang::Parameter* direct = parameter(model, templ.path + (is_maxwell ? ".c" : ".fy"));
  const bool by_ratio = tau && tau->value_begin >= 0;
  const std::vector<double> spread = is_maxwell ? log_spread(spreads.tau.front(), spreads.tau.back(), count)
                                                : log_spread(spreads.uy.front(), spreads.uy.back(), count);
  std::string out;
  for (int i = 0; i < count; ++i) {
    const std::string name = fmt::format("{}{}", is_maxwell ? "order_m" : "order_f", i + 1);
    const std::string second = by_ratio ? argument(*tau, is_maxwell ? "tau" : "uy", spread[static_cast<std::size_t>(i)])
                                        : argument(*direct, is_maxwell ? "c" : "fy", k->value * spread[static_cast<std::size_t>(i)]);
    out += fmt::format("  {} {} ({}, {})\n", lang::kind_word(templ.kind), name, argument(*k, "k", k->value), second);
  }
  return out;
}

Spreads spreads_of(const std::vector<runtime::FitDataSet>& data) {
  double f_lo = 1.0, f_hi = 50.0, a_lo = 0.01, a_hi = 1.0;
  bool harmonic = false;
  for (const auto& set : data) {
    if (!set.is_harmonic()) continue;
    const auto& h = set.harmonic();
    const auto [fl, fh] = std::minmax_element(h.frequency.begin(), h.frequency.end());
    const auto [al, ah] = std::minmax_element(h.amplitude.begin(), h.amplitude.end());
    f_lo = harmonic ? std::min(f_lo, *fl) : *fl, f_hi = harmonic ? std::max(f_hi, *fh) : *fh;
    a_lo = harmonic ? std::min(a_lo, *al) : *al, a_hi = harmonic ? std::max(a_hi, *ah) : *ah;
    harmonic = true;
  }
  const double two_pi = 2.0 * std::numbers::pi;
  return {{1.0 / (two_pi * f_hi), 1.0 / (two_pi * f_lo)}, {a_lo / 4.0, a_hi / 2.0}};
}

}  // namespace

int run_order_study(const std::vector<FitJob>& jobs, const FitOptions& options) {
  if (jobs.size() != 1) throw runtime::UsageError("--orders studies one fit; select it with --model");
  const FitJob& job = jobs.front();
  const lang::CheckedModel& model = *job.model;
  const OrderSpec spec = parse_orders(options.orders);
  const lang::Element* maxwell_template = nullptr;
  const lang::Element* friction_template = nullptr;
  std::string kept;
  for (const auto& e : model.root.children) {
    if (e.kind == lang::ElementKind::parallel || e.kind == lang::ElementKind::series)
      throw runtime::UsageError(fmt::format("--orders needs a model whose elements all act in parallel; '{}' in model '{}' is a {} block",
                                            e.path, model.name, e.kind == lang::ElementKind::series ? "series" : "parallel"));
    if (e.kind == lang::ElementKind::maxwell && spec.maxwell) {
      if (!maxwell_template) maxwell_template = &e;
    } else if (e.kind == lang::ElementKind::friction && spec.friction) {
      if (!friction_template) friction_template = &e;
    } else {
      kept += fmt::format("  {} {} ({})\n", lang::kind_word(e.kind), e.name, arguments_of(model, e));
    }
  }
  if (spec.maxwell && !maxwell_template)
    throw runtime::UsageError(fmt::format("--orders maxwell=...: model '{}' has no maxwell element to copy bounds from; add one", model.name));
  if (spec.friction && !friction_template)
    throw runtime::UsageError(fmt::format("--orders friction=...: model '{}' has no friction element to copy bounds from; add one", model.name));
  const Spreads spreads = spreads_of(job.data);
  const CountRange maxwells = spec.maxwell.value_or(CountRange{-1, -1}), frictions = spec.friction.value_or(CountRange{-1, -1});

  nlohmann::json rows = nlohmann::json::array();
  if (!options.json)
    std::cout << fmt::format("model-order study of {} (method {}): err (6.1) on all harmonic data\n{:>10}  {:>10}  {:>10}  {:>12}  {:>8}\n",
                             model.name, job.description.method, "maxwell", "friction", "parameters", "err", "seconds");
  for (int m = maxwells.first; m <= maxwells.last; ++m)
    for (int f = frictions.first; f <= frictions.last; ++f) {
      std::string source = fmt::format("model {} {{\n{}", model.name, kept);
      if (m >= 0) source += copies(model, *maxwell_template, m, spreads);
      if (f >= 0) source += copies(model, *friction_template, f, spreads);
      source += "}\n";
      const lang::Program variant = lang::compile_source(fmt::format("<order study {}x{}>", m, f), source);
      FitJob v = job;
      v.model = variant.find_model(model.name);
      v.free = lang::default_free_parameters(*v.model);
      const runtime::FitResult r = run_fit_job(v);
      rows.push_back({{"maxwell", std::max(m, 0)}, {"friction", std::max(f, 0)}, {"parameters", r.free.size()}, {"err", r.err},
                      {"phi", r.phi}, {"evaluations", r.evaluations}, {"wall_seconds", r.wall_seconds}});
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
