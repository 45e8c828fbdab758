#include "lang/checker.hpp"

#include "lang/dependency_order.hpp"
#include "lang/element_schema.hpp"
#include "lang/fit_schema.hpp"
#include "lang/model_builder.hpp"
#include "lang/names.hpp"
#include "lang/protocol_schema.hpp"
#include "lang/setting_values.hpp"

#include <fmt/format.h>

#include <map>

namespace rheo::lang {
namespace {

class Checker {
 public:
  Checker(std::vector<Diagnostic>& errors) : errors_(errors) {}

  void declare(const ast::Model& m) {
    auto [it, fresh] = declared_.emplace(m.name, static_cast<int>(order_.size()));
    if (!fresh) {
      const auto& first = order_[static_cast<std::size_t>(it->second)]->where;
      errors_.push_back({m.where, fmt::format("duplicate model '{}' (first defined at {}:{}); rename one", m.name, first.file, first.line)});
      return;
    }
    order_.push_back(&m);
  }

  // Checks every declared model, each after the models it instantiates.
  std::vector<CheckedModel> check_models() {
    visit_in_dependency_order(
        order_.size(), [this](int i) { return instances(*order_[static_cast<std::size_t>(i)]); },
        [this](int i) { check(*order_[static_cast<std::size_t>(i)]); },
        [this](const std::vector<int>& cycle, const Instance& edge) { report_recursion(cycle, edge); });
    std::vector<CheckedModel> out;
    for (const auto* m : order_) out.push_back(done_.at(m->name).model);
    return out;
  }

  bool known_model(const std::string& name) const { return declared_.count(name) != 0; }
  // The checked model NAME, or nullptr when it is unknown or has errors.
  const CheckedModel* checked_model(const std::string& name) const {
    auto it = done_.find(name);
    return it != done_.end() && it->second.ok ? &it->second.model : nullptr;
  }
  std::vector<std::string> model_names() const {
    std::vector<std::string> out;
    for (const auto* m : order_) out.push_back(m->name);
    return out;
  }

 private:
  struct Instance {
    int to;  // into order_
    const ast::Element* element;
  };

  // The declared models that model M instantiates, in the order they are written.
  std::vector<Instance> instances(const ast::Model& m) const {
    std::vector<Instance> out;
    collect_instances(m.elements, out);
    return out;
  }
  void collect_instances(const std::vector<ast::Element>& elements, std::vector<Instance>& out) const {
    for (const auto& e : elements) {
      if (e.block) collect_instances(e.children, out);
      else if (auto it = declared_.find(e.kind); it != declared_.end() && !find_element_spec(e.kind)) out.push_back({it->second, &e});
    }
  }

  void check(const ast::Model& m) {
    ModelLookup lookup = [this, &m](const ast::Element& e) { return instantiate(e, m.name); };
    done_.emplace(m.name, build_model(m, lookup, errors_));
  }

  void report_recursion(const std::vector<int>& cycle, const Instance& edge) {
    std::vector<std::string> chain;
    for (int i : cycle) chain.push_back(order_[static_cast<std::size_t>(i)]->name);
    chain.push_back(edge.element->kind);
    errors_.push_back({edge.element->where, fmt::format("recursive instantiation: {}; a model cannot contain itself", join_chain(chain))});
  }

  // The model element E of model OWNER names, or nullptr when it is unknown (reported here, with
  // the kinds and models it could name: never OWNER itself, which cannot contain itself) or failed.
  const ModelInfo* instantiate(const ast::Element& e, const std::string& owner) {
    if (!declared_.count(e.kind)) {
      if (known_kinds_.empty()) {
        for (const auto& s : element_specs()) known_kinds_.emplace_back(s.kind);
        for (const auto& [name, index] : declared_) known_kinds_.push_back(name);
      }
      std::vector<std::string> known;
      for (const auto& kind : known_kinds_)
        if (kind != owner || find_element_spec(kind)) known.push_back(kind);
      errors_.push_back({e.where, fmt::format("unknown element kind or model '{}';{} known: {} (and parallel, series blocks); "
                                              "stdlib models need `import NAME`",
                                              e.kind, did_you_mean(e.kind, known), join(known))});
      return nullptr;
    }
    // Checked before its users (check_models), unless it is on a reported recursion.
    auto it = done_.find(e.kind);
    return it != done_.end() && it->second.ok ? &it->second : nullptr;
  }

  std::vector<Diagnostic>& errors_;
  std::map<std::string, int> declared_;  // name -> index into order_
  std::vector<const ast::Model*> order_;
  std::map<std::string, ModelInfo> done_;
  std::vector<std::string> known_kinds_;  // element kinds and models, for suggestions; filled on first use
};

// The model a `simulate`/`fit` block (DIRECTIVE) names, or the file's only (non-imported)
// model when it names none; "" after reporting when there is none.
std::string resolve_model(const std::string& directive, const std::string& named, const SourceLocation& named_where, const SourceLocation& where,
                          const ast::File& file, const Checker& checker, std::vector<Diagnostic>& errors) {
  if (!named.empty()) {
    if (checker.known_model(named)) return named;
    errors.push_back({named_where, fmt::format("{} names unknown model '{}';{} known: {}", directive, named,
                                               did_you_mean(named, checker.model_names()), join(checker.model_names()))});
  } else if (file.models.size() == 1) {
    return file.models.front().name;
  } else if (file.models.empty()) {
    errors.push_back({where, fmt::format("this file defines no model; name the one to {0}: {0} NAME {{ ... }}", directive)});
  } else {
    errors.push_back({where, fmt::format("this file defines several models; name one: {} NAME {{ ... }}", directive)});
  }
  return "";
}

SimulateDirective check_simulate(const ast::Simulate& s, const ast::File& file, const Checker& checker, std::vector<Diagnostic>& errors) {
  SimulateDirective out{resolve_model("simulate", s.model, s.model_where, s.where, file, checker, errors), {}, s.where};
  enum class Last { nothing, protocol, unknown_protocol, output } last = Last::nothing;
  for (const auto& line : s.lines) {
    if (line.output) {
      if (last == Last::protocol && check_file_name(line.file, line.where, errors)) out.protocols.back().output = line.file;
      else if (last == Last::nothing)
        errors.push_back({line.where, "'output' names the results of the protocol line before it, but there is none; put it after a protocol line"});
      else if (last == Last::output) errors.push_back({line.where, "a protocol line has only one 'output'; remove this one"});
      last = Last::output;
      continue;
    }
    auto kind = protocol_kind(line.kind);
    if (!kind) {
      errors.push_back({line.where, fmt::format("unknown protocol '{}';{} known: {}", line.kind, did_you_mean(line.kind, protocol_names()),
                                                join(protocol_names()))});
      last = Last::unknown_protocol;
      continue;
    }
    out.protocols.push_back(check_protocol(*kind, line.settings, line.where, errors));
    last = Last::protocol;
  }
  if (s.lines.empty())
    errors.push_back({s.where, "empty simulate block; add a protocol line such as `harmonic frequency = 10 Hz, amplitude = 1 mm`"});
  return out;
}

}  // namespace

Program check(const ast::File& file, const std::vector<const ast::File*>& imported, std::vector<Diagnostic>& errors) {
  Checker checker(errors);
  for (const auto* module : imported)
    for (const auto& m : module->models) checker.declare(m);
  for (const auto& m : file.models) checker.declare(m);
  Program program;
  program.models = checker.check_models();
  for (const auto& s : file.simulations) program.simulations.push_back(check_simulate(s, file, checker, errors));
  for (const auto& f : file.fits) {
    std::string model = resolve_model("fit", f.model, f.model_where, f.where, file, checker, errors);
    program.fits.push_back(check_fit(f, model, model.empty() ? nullptr : checker.checked_model(model), errors));
  }
  return program;
}

}  // namespace rheo::lang
