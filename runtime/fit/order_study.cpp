#include "runtime/fit/order_study.hpp"

#include "lang/fitted_source.hpp"
#include "runtime/core/errors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rheo::runtime {
namespace {

std::vector<double> log_spread(double lo, double hi, int count) {
  std::vector<double> v;
  for (int i = 0; i < count; ++i) v.push_back(count == 1 ? std::sqrt(lo * hi) : lo * std::pow(hi / lo, static_cast<double>(i) / (count - 1)));
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


// The copies of `templ` (a maxwell or friction leaf), as source lines.
std::string copies(const lang::CheckedModel& model, const lang::Element& templ, int count, const StartSpreads& spreads) {
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

StartSpreads spreads_of(const std::vector<runtime::FitDataSet>& data) {
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

OrderStudy::OrderStudy(const lang::CheckedModel& model, const OrderSpec& spec, const std::vector<FitDataSet>& data)
    : model_(model), spec_(spec), spreads_(spreads_of(data)) {
  for (const auto& e : model.root.children) {
    if (e.kind == lang::ElementKind::parallel || e.kind == lang::ElementKind::series)
      throw UsageError(fmt::format("--orders needs a model whose elements all act in parallel; '{}' in model '{}' is a {} block", e.path,
                                   model.name, e.kind == lang::ElementKind::series ? "series" : "parallel"));
    if (e.kind == lang::ElementKind::maxwell && spec.maxwell) {
      if (!maxwell_template_) maxwell_template_ = &e;
    } else if (e.kind == lang::ElementKind::friction && spec.friction) {
      if (!friction_template_) friction_template_ = &e;
    } else {
      kept_ += fmt::format("  {} {} ({})\n", lang::kind_word(e.kind), e.name, arguments_of(model, e));
    }
  }
  if (spec.maxwell && !maxwell_template_)
    throw UsageError(fmt::format("--orders maxwell=...: model '{}' has no maxwell element to copy bounds from; add one", model.name));
  if (spec.friction && !friction_template_)
    throw UsageError(fmt::format("--orders friction=...: model '{}' has no friction element to copy bounds from; add one", model.name));
}

std::vector<OrderStudy::Variant> OrderStudy::variants() const {
  const CountRange maxwells = spec_.maxwell.value_or(CountRange{-1, -1}), frictions = spec_.friction.value_or(CountRange{-1, -1});
  std::vector<Variant> out;
  for (int m = maxwells.first; m <= maxwells.last; ++m)
    for (int f = frictions.first; f <= frictions.last; ++f) {
      std::string source = fmt::format("model {} {{\n{}", model_.name, kept_);
      if (m >= 0) source += copies(model_, *maxwell_template_, m, spreads_);
      if (f >= 0) source += copies(model_, *friction_template_, f, spreads_);
      source += "}\n";
      out.push_back({m, f, std::move(source)});
    }
  return out;
}

namespace {

double value_at(const lang::CheckedModel& model, const std::vector<double>& values, const std::string& path) {
  for (std::size_t i = 0; i < model.parameters.size(); ++i)
    if (model.parameters[i].path == path) return values[i];
  return 0.0;
}

// The shape of a copy, tau [s] or uy [mm], from its parameters' values.
double shape_of(const lang::CheckedModel& model, const std::vector<double>& values, const lang::Element& e) {
  const double k = value_at(model, values, e.path + ".k");
  return k > 0.0 ? value_at(model, values, e.path + (e.kind == lang::ElementKind::maxwell ? ".c" : ".fy")) / k : 0.0;
}

// The geometric middle of the widest log gap between LO, the positive SHAPES and HI.
double widest_gap(double lo, double hi, std::vector<double> shapes) {
  shapes.erase(std::remove_if(shapes.begin(), shapes.end(), [](double v) { return !(v > 0.0); }), shapes.end());
  shapes.push_back(lo), shapes.push_back(hi);
  std::sort(shapes.begin(), shapes.end());
  double best = std::sqrt(lo * hi), widest = -1.0;
  for (std::size_t i = 0; i + 1 < shapes.size(); ++i)
    if (const double gap = std::log(shapes[i + 1] / shapes[i]); gap > widest) widest = gap, best = std::sqrt(shapes[i] * shapes[i + 1]);
  return best;
}

// Sets the written parameter PATH of VARIANT in START (clamped into its bounds when free).
void set_written(const lang::CheckedModel& variant, std::vector<double>& start, const std::string& path, double value) {
  for (std::size_t i = 0; i < variant.parameters.size(); ++i) {
    const lang::Parameter& p = variant.parameters[i];
    if (p.path == path && p.expression.is_constant()) start[i] = p.free ? std::clamp(value, p.lower, p.upper) : value;
  }
}

}  // namespace

std::vector<double> OrderStudy::warm_start(const lang::CheckedModel& variant, const lang::CheckedModel& previous,
                                           const std::vector<double>& fitted) const {
  std::vector<double> start;
  for (const auto& p : variant.parameters) start.push_back(p.value);
  auto in_previous = [&](const std::string& path) {
    return std::any_of(previous.parameters.begin(), previous.parameters.end(), [&](const lang::Parameter& p) { return p.path == path; });
  };
  for (const auto& p : previous.parameters) set_written(variant, start, p.path, value_at(previous, fitted, p.path));
  for (const auto& e : variant.root.children) {
    if (in_previous(e.path + ".k") || (e.kind != lang::ElementKind::maxwell && e.kind != lang::ElementKind::friction)) continue;
    const bool is_maxwell = e.kind == lang::ElementKind::maxwell;
    const std::string shape_name = is_maxwell ? ".tau" : ".uy", force_name = is_maxwell ? ".c" : ".fy";
    // The previous structure's stiffest copy of the family, split in two equal halves.
    const lang::Element* stiffest = nullptr;
    std::vector<double> shapes;
    for (const auto& other : previous.root.children) {
      if (other.kind != e.kind) continue;
      shapes.push_back(shape_of(previous, fitted, other));
      if (!stiffest || value_at(previous, fitted, other.path + ".k") > value_at(previous, fitted, stiffest->path + ".k")) stiffest = &other;
    }
    if (stiffest) {
      const double k = value_at(previous, fitted, stiffest->path + ".k"), shape = shape_of(previous, fitted, *stiffest);
      for (const std::string& path : {stiffest->path, e.path}) {
        set_written(variant, start, path + ".k", 0.5 * k);
        set_written(variant, start, path + shape_name, shape);
        set_written(variant, start, path + force_name, 0.5 * k * shape);
      }
      continue;
    }
    // None to split: k at its lower bound, the shape in the widest gap of the data's spread.
    const auto& range = is_maxwell ? spreads_.tau : spreads_.uy;
    const double shape = widest_gap(range.front(), range.back(), shapes);
    double k = 0.0;
    for (std::size_t i = 0; i < variant.parameters.size(); ++i)
      if (variant.parameters[i].path == e.path + ".k") k = variant.parameters[i].free ? variant.parameters[i].lower : start[i];
    set_written(variant, start, e.path + ".k", k);
    set_written(variant, start, e.path + shape_name, shape);
    set_written(variant, start, e.path + force_name, k * shape);
  }
  return start;
}

}  // namespace rheo::runtime
