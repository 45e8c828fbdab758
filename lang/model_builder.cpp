#include "lang/model_builder.hpp"

#include "lang/dependency_order.hpp"
#include "lang/element_schema.hpp"
#include "lang/expressions.hpp"
#include "lang/limits.hpp"
#include "lang/names.hpp"
#include "lang/parameter_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

namespace rheo::lang {
namespace {

// A parameter while its model is being checked: either source (an expression in this model's
// namespace) or copied from an instantiated model (already compiled, indices remapped).
struct Entry {
  Parameter parameter;
  ParameterMeta meta;
  bool dimension_known = false;  // element parameters; model `param`s infer theirs
  const ast::Expr* source = nullptr;
  const ast::Bounds* bounds = nullptr;
  enum class State { pending, done, failed } state = State::pending;
};

// Names within one naming scope (model root, named block, instance).
struct Scope {
  std::string prefix;  // "fluid." ; "" at the model root
  std::map<std::string, SourceLocation> names;
  std::map<std::string, int> counters;  // per kind, for generated names
};

class Builder {
 public:
  Builder(const ast::Model& model, const ModelLookup& lookup, std::vector<Diagnostic>& errors)
      : model_(model), lookup_(lookup), errors_(errors), first_error_(errors.size()) {}

  ModelInfo run() {
    for (const auto& p : model_.parameters) add_model_parameter(p);
    Scope root;
    info_.model.name = model_.name;
    info_.model.where = model_.where;
    info_.model.root.kind = ElementKind::parallel;
    info_.model.root.where = model_.where;
    if (model_.elements.empty()) error(model_.where, fmt::format("model '{}' has no elements; add at least one element to its body", model_.name));
    info_.model.root.children = build_scope(model_.elements, root, 0);
    values_.assign(entries_.size(), 0.0);
    resolve_all();
    for (auto& e : entries_) {
      info_.model.parameters.push_back(std::move(e.parameter));
      info_.meta.push_back(std::move(e.meta));
    }
    info_.ok = errors_.size() == first_error_ && info_.ok;
    return std::move(info_);
  }

 private:
  void error(const SourceLocation& where, std::string message) { errors_.push_back({where, std::move(message)}); }

  // Where P's value is written: argument A of this model's source.
  static void locate(Parameter& p, const ast::Argument& a) {
    p.where = a.value_where;
    p.unit = literal_unit(*a.value);
    p.value_begin = a.value_begin;
    p.value_end = a.value_end;
  }

  int add(Entry e) {
    int index = static_cast<int>(entries_.size());
    index_[e.parameter.path] = index;
    entries_.push_back(std::move(e));
    return index;
  }

  // --- declarations ---
  void add_model_parameter(const ast::Argument& a) {
    if (auto it = index_.find(a.name); it != index_.end()) {
      error(a.where, fmt::format("duplicate parameter '{}' (first declared at line {}); rename one", a.name,
                                 entries_[static_cast<std::size_t>(it->second)].parameter.where.line));
      return;
    }
    if (a.name.find('.') != std::string::npos) {
      error(a.where, fmt::format("model parameter names cannot contain '.': '{}'", a.name));
      return;
    }
    Entry e;
    e.parameter.path = a.name;
    locate(e.parameter, a);
    e.source = a.value.get();
    e.bounds = a.bounds ? &*a.bounds : nullptr;
    add(std::move(e));
  }

  // Registers the explicit names of ELEMENTS (looking through unnamed blocks) in SCOPE.
  void collect_names(const std::vector<ast::Element>& elements, Scope& scope) {
    for (const auto& e : elements) {
      if (!e.name.empty()) {
        auto [it, fresh] = scope.names.emplace(e.name, e.name_where);
        if (!fresh)
          error(e.name_where, fmt::format("duplicate name '{}' (first used at line {}); element names must be unique within their block", e.name,
                                          it->second.line));
      } else if (e.block) {
        collect_names(e.children, scope);
      }
    }
  }

  std::string generate_name(const std::string& kind, Scope& scope) {
    for (int& n = scope.counters[kind];;) {
      std::string name = kind + std::to_string(++n);
      if (scope.names.emplace(name, SourceLocation{}).second) return name;
    }
  }

  // DEPTH: the blocks around ELEMENTS, 0 in the model's body.
  std::vector<Element> build_scope(const std::vector<ast::Element>& elements, Scope& scope, int depth) {
    collect_names(elements, scope);
    return build_children(elements, scope, depth);
  }

  std::vector<Element> build_children(const std::vector<ast::Element>& elements, Scope& scope, int depth) {
    std::vector<Element> out;
    for (const auto& e : elements) {
      std::string name = e.name.empty() ? generate_name(e.kind, scope) : e.name;
      std::string path = scope.prefix + name;
      if (e.block) {
        if (e.children.empty()) error(e.where, fmt::format("empty {} block; add elements to it or remove it", e.kind));
        Element block{e.kind == "series" ? ElementKind::series : ElementKind::parallel, name, path, {}, {}, e.where};
        if (e.name.empty()) {
          block.children = build_children(e.children, scope, depth + 1);  // unnamed blocks are transparent
        } else {
          Scope inner{path + ".", {}, {}};
          block.children = build_scope(e.children, inner, depth + 1);
        }
        out.push_back(std::move(block));
      } else if (const ElementSpec* spec = find_element_spec(e.kind)) {
        if (auto leaf = build_leaf(e, *spec, name, path)) out.push_back(std::move(*leaf));
      } else if (const ModelInfo* instance = lookup_(e); instance && fits_limits(e, *instance, depth)) {
        out.push_back(build_instance(e, *instance, name, path));
      } else {
        info_.ok = false;  // reported by the lookup, by fits_limits or where the instantiated model failed
      }
    }
    return out;
  }

  std::optional<Element> build_leaf(const ast::Element& e, const ElementSpec& spec, const std::string& name, const std::string& path) {
    std::vector<std::string> accepted;
    for (const auto& s : spec.slots) accepted.emplace_back(s.name);
    for (const auto& s : spec.alternative) accepted.emplace_back(s.name);
    for (const auto& s : spec.split) accepted.emplace_back(s.name);
    const std::string what = describe_element(spec.kind, path);
    std::map<std::string, const ast::Argument*> given;
    // Parameters an unknown one was taken for ("tua": "did you mean 'tau'?"): their absence is
    // that message's, not another.
    std::set<std::string> suggested;
    for (const auto& a : e.arguments) {
      if (std::find(accepted.begin(), accepted.end(), a.name) == accepted.end()) {
        const std::string nearest = closest(a.name, accepted);
        if (!nearest.empty()) suggested.insert(nearest);
        error(a.where, fmt::format("unknown parameter '{}' for {};{} it accepts {}", a.name, what, did_you_mean(a.name, accepted), join(accepted)));
      } else if (auto [it, fresh] = given.emplace(a.name, &a); !fresh) {
        error(a.where, fmt::format("duplicate parameter '{}' for {} (first given at line {}); give it once", a.name, what, it->second->where.line));
      }
    }
    bool ok = true;
    std::optional<std::size_t> derived_slot;
    const int split_given = count_split(spec, given);
    if (split_given > 0 && !check_split(e, spec, given, what)) ok = false;
    for (std::size_t i = 0; i < spec.slots.size(); ++i) {
      const bool last = i + 1 == spec.slots.size();
      const bool has_slot = given.count(std::string(spec.slots[i].name)) != 0;
      if (last && split_given > 0) {
        // the split stands for the last slot (checked above)
      } else if (last && !spec.alternative.empty()) {
        std::string alt(spec.alternative[0].name);
        const bool has_alt = given.count(alt) != 0;
        if (has_slot && has_alt) {
          const auto* second = std::max(given[alt], given[std::string(spec.slots[i].name)], [](auto* a, auto* b) {
            return a->where.line != b->where.line ? a->where.line < b->where.line : a->where.column < b->where.column;
          });
          // Reported; checking goes on with the primary parameter so its other errors surface too.
          error(second->where, fmt::format("{} takes either {} or {}, not both; remove one", what, alt, spec.slots[i].name));
        } else if (!has_slot && !has_alt) {
          if (!suggested.count(alt) && !suggested.count(std::string(spec.slots[i].name)))
            error(e.where, fmt::format("{} is missing its {} {} (or {} {}); add `{} = ...`", what, spec.alternative[0].quantity, alt,
                                       spec.slots[i].quantity, spec.slots[i].name, alt));
          ok = false;
        } else if (has_alt) {
          derived_slot = i;
        }
      } else if (!has_slot && !spec.slots[i].default_value) {
        if (!suggested.count(std::string(spec.slots[i].name)))
          error(e.where, fmt::format("{} is missing its {} {} ({}); add `{} = ...`", what, spec.slots[i].quantity, spec.slots[i].name,
                                     internal_unit(spec.slots[i].dimension), spec.slots[i].name));
        ok = false;
      }
    }
    if (!ok) return std::nullopt;
    Element out{spec.element_kind, name, path, {}, {}, e.where};
    for (std::size_t i = 0; i < spec.slots.size(); ++i) {
      if (split_given > 0 && i + 1 == spec.slots.size()) {
        for (const auto& side : spec.split) out.parameters.push_back(add_element_parameter(*given[std::string(side.name)], side, spec.kind, path));
      } else if (derived_slot == i) {
        int alt = add_element_parameter(*given[std::string(spec.alternative[0].name)], spec.alternative[0], spec.kind, path);
        Entry derived;
        derived.parameter.path = path + "." + std::string(spec.slots[i].name);
        derived.parameter.dimension = spec.slots[i].dimension;
        derived.parameter.expression.code = {{Expression::Op::parameter, 0.0, out.parameters[0]},
                                             {Expression::Op::parameter, 0.0, alt},
                                             {Expression::Op::multiply}};
        derived.parameter.where = entries_[static_cast<std::size_t>(alt)].parameter.where;
        derived.meta = {false, true, std::string(spec.slots[i].quantity), std::string(spec.kind)};
        derived.dimension_known = true;
        out.parameters.push_back(add(std::move(derived)));
      } else if (auto it = given.find(std::string(spec.slots[i].name)); it != given.end()) {
        out.parameters.push_back(add_element_parameter(*it->second, spec.slots[i], spec.kind, path));
      } else {
        out.parameters.push_back(add_default_parameter(e, spec.slots[i], spec.kind, path));
      }
    }
    return out;
  }

  // How many of SPEC's split parameters (fy_pos, fy_neg) are given.
  static int count_split(const ElementSpec& spec, const std::map<std::string, const ast::Argument*>& given) {
    int n = 0;
    for (const auto& side : spec.split) n += given.count(std::string(side.name)) != 0 ? 1 : 0;
    return n;
  }

  // A split given: both of its sides, and neither the slot it replaces nor that slot's alternative.
  bool check_split(const ast::Element& e, const ElementSpec& spec, const std::map<std::string, const ast::Argument*>& given, const std::string& what) {
    const ParameterSpec& slot = spec.slots.back();
    std::vector<std::string> others{std::string(slot.name)};
    for (const auto& a : spec.alternative) others.emplace_back(a.name);
    bool ok = true;
    for (const auto& other : others)
      if (auto it = given.find(other); it != given.end()) {
        error(it->second->where, fmt::format("{} takes either {} or {} and {}, not both; remove {} or the pair", what, other, spec.split[0].name,
                                             spec.split[1].name, other));
        ok = false;
      }
    for (std::size_t i = 0; i < spec.split.size(); ++i)
      if (!given.count(std::string(spec.split[i].name))) {
        const ParameterSpec& missing = spec.split[i];
        error(e.where, fmt::format("{} is given {} but not its {} {}; add `{} = ...` (or give {} alone for equal yield forces)", what,
                                   spec.split[1 - i].name, missing.quantity, missing.name, missing.name, slot.name));
        ok = false;
      }
    return ok;
  }

  int add_element_parameter(const ast::Argument& a, const ParameterSpec& spec, std::string_view kind, const std::string& path) {
    Entry e;
    e.parameter.path = path + "." + a.name;
    e.parameter.dimension = spec.dimension;
    locate(e.parameter, a);
    e.meta = {spec.positive, false, std::string(spec.quantity), std::string(kind), spec.below};
    e.dimension_known = true;
    e.source = a.value.get();
    e.bounds = a.bounds ? &*a.bounds : nullptr;
    return add(std::move(e));
  }

  // An optional parameter left out: a constant with the spec's default, located at the element.
  int add_default_parameter(const ast::Element& element, const ParameterSpec& spec, std::string_view kind, const std::string& path) {
    Entry e;
    e.parameter.path = path + "." + std::string(spec.name);
    e.parameter.dimension = spec.dimension;
    e.parameter.expression.code = {{Expression::Op::constant, *spec.default_value, -1}};
    e.parameter.where = element.where;
    e.meta = {spec.positive, false, std::string(spec.quantity), std::string(kind), spec.below};
    e.dimension_known = true;
    return add(std::move(e));
  }

  struct Extent {
    int levels = 0;        // blocks on the longest path down, the element itself included
    std::size_t size = 0;  // elements
  };
  static Extent extent(const Element& e) {
    Extent out{e.kind == ElementKind::parallel || e.kind == ElementKind::series ? 1 : 0, 1};
    int below = 0;
    for (const auto& c : e.children) {
      const Extent x = extent(c);
      below = std::max(below, x.levels);
      out.size += x.size;
    }
    out.levels += below;
    return out;
  }

  // Whether INSTANCE, expanded at DEPTH (the blocks around it), keeps this model within
  // limits.hpp; reports at the instance when not.
  bool fits_limits(const ast::Element& e, const ModelInfo& instance, int depth) {
    const Extent x = extent(instance.model.root);  // the root is the instance's block
    if (depth + x.levels > max_block_depth) {
      error(e.where, fmt::format("instantiating model '{}' here nests blocks {} levels deep, more than {} (an instance is a block, "
                                 "and the blocks and instances inside it count too); flatten the models or instantiate this one "
                                 "less deeply",
                                 e.kind, depth + x.levels, max_block_depth));
      return false;
    }
    const std::size_t size = x.size + instance.model.parameters.size();
    if (expanded_ + size > max_model_size) {
      error(e.where, fmt::format("instantiating model '{}' here expands model '{}' to more than {} elements and parameters "
                                 "(this instance copies {}); instantiate large models fewer times",
                                 e.kind, model_.name, max_model_size, size));
      return false;
    }
    expanded_ += size;
    return true;
  }

  // The instantiated model's root becomes a parallel block named by the instance; its
  // parameters are copied under the instance's path, then overridden by the arguments.
  Element build_instance(const ast::Element& e, const ModelInfo& instance, const std::string& name, const std::string& path) {
    const int base = static_cast<int>(entries_.size());
    for (std::size_t i = 0; i < instance.model.parameters.size(); ++i) {
      Entry copy;
      copy.parameter = instance.model.parameters[i];
      copy.parameter.path = path + "." + copy.parameter.path;
      copy.parameter.value_begin = copy.parameter.value_end = -1;  // the instantiated model's text, shared
      for (auto& op : copy.parameter.expression.code)
        if (op.op == Expression::Op::parameter) op.parameter += base;
      copy.meta = instance.meta[i];
      copy.dimension_known = true;
      add(std::move(copy));
    }
    std::vector<std::string> overridable;
    for (std::size_t i = 0; i < instance.model.parameters.size(); ++i)
      if (!instance.meta[i].derived) overridable.push_back(instance.model.parameters[i].path);
    std::map<std::string, const ast::Argument*> given;
    for (const auto& a : e.arguments) {
      auto it = index_.find(path + "." + a.name);
      if (it == index_.end() || it->second < base) {
        error(a.where,
              fmt::format("model '{}' has no parameter '{}';{} it has {}", e.kind, a.name, did_you_mean(a.name, overridable), join(overridable)));
        continue;
      }
      Entry& target = entries_[static_cast<std::size_t>(it->second)];
      if (target.meta.derived) {
        error(a.where,
              fmt::format("'{}' of model '{}' is computed from other parameters and cannot be overridden; override those instead", a.name, e.kind));
      } else if (auto [first, fresh] = given.emplace(a.name, &a); !fresh) {
        error(a.where, fmt::format("duplicate override of '{}' (first given at line {}); give it once", a.name, first->second->where.line));
      } else {
        // Override expressions are written in the enclosing model's namespace.
        target.source = a.value.get();
        target.bounds = a.bounds ? &*a.bounds : nullptr;
        target.parameter.free = false;
        locate(target.parameter, a);
      }
    }
    Element root = instance.model.root;
    rebase(root, path, base);
    root.name = name;
    root.where = e.where;
    return root;
  }

  static void rebase(Element& e, const std::string& path, int base) {
    e.path = e.path.empty() ? path : path + "." + e.path;
    for (int& p : e.parameters) p += base;
    for (auto& c : e.children) rebase(c, path, base);
  }

  // --- resolution: dimensions, expressions, values ---
  struct Dependency {
    int to;  // entry
  };

  // The entries entry I is computed from, in the order its expression names them (unknown
  // names are left to the compilation to report).
  std::vector<Dependency> dependencies(int i) const {
    std::vector<Dependency> out;
    const Entry& e = entries_[static_cast<std::size_t>(i)];
    if (e.source) {
      collect_references(*e.source, out);
    } else {
      for (const auto& op : e.parameter.expression.code)
        if (op.op == Expression::Op::parameter) out.push_back({op.parameter});
    }
    return out;
  }

  void collect_references(const ast::Expr& x, std::vector<Dependency>& out) const {
    if (x.kind == ast::Expr::Kind::reference) {
      if (auto it = index_.find(x.path); it != index_.end()) out.push_back({it->second});
      return;
    }
    if (x.lhs) collect_references(*x.lhs, out);
    if (x.rhs) collect_references(*x.rhs, out);
  }

  // Resolves every entry after the entries it references, however long the chains.
  void resolve_all() {
    visit_in_dependency_order(
        entries_.size(), [this](int i) { return dependencies(i); }, [this](int i) { resolve(i); },
        [this](const std::vector<int>& cycle, const Dependency&) { report_cycle(cycle); });
  }

  std::optional<ResolvedReference> reference(const ast::Expr& r) {
    auto it = index_.find(r.path);
    if (it == index_.end()) {
      if (known_paths_.empty())
        for (const auto& [path, index] : index_) known_paths_.push_back(path);
      error(r.where, fmt::format("unknown parameter '{}' in this expression;{} references name parameters of model '{}' by path, e.g. k0 or m1.k",
                                 r.path, did_you_mean(r.path, known_paths_), model_.name));
      return std::nullopt;
    }
    // Resolved before this one (resolve_all); a failed one was reported where it failed.
    if (entries_[static_cast<std::size_t>(it->second)].state != Entry::State::done) return std::nullopt;
    return ResolvedReference{it->second, entries_[static_cast<std::size_t>(it->second)].parameter.dimension};
  }

  // Compiles, evaluates and checks entry I; everything it references is resolved or failed.
  void resolve(int i) {
    bool ok = entries_[static_cast<std::size_t>(i)].source ? compile_source(i) : resolve_copied(i);
    Entry& done = entries_[static_cast<std::size_t>(i)];
    if (done.state == Entry::State::failed) return;  // part of a reported cycle
    if (ok) {
      values_[static_cast<std::size_t>(i)] = done.parameter.value = done.parameter.expression.evaluate(values_);
      ok = check_value(done.parameter, done.meta, errors_) && (!done.bounds || check_bounds(done.parameter, done.meta, *done.bounds, errors_));
    }
    done.state = ok ? Entry::State::done : Entry::State::failed;
  }

  void report_cycle(const std::vector<int>& cycle) {
    std::vector<std::string> chain;
    for (int i : cycle) {
      chain.push_back(entries_[static_cast<std::size_t>(i)].parameter.path);
      entries_[static_cast<std::size_t>(i)].state = Entry::State::failed;
    }
    const Entry& e = entries_[static_cast<std::size_t>(cycle.front())];
    chain.push_back(e.parameter.path);
    error(e.parameter.where, fmt::format("reference cycle: {}; a parameter cannot depend on itself", join_chain(chain)));
  }

  bool resolve_copied(int i) {
    bool ok = true;
    for (const auto& op : entries_[static_cast<std::size_t>(i)].parameter.expression.code)
      if (op.op == Expression::Op::parameter) ok = entries_[static_cast<std::size_t>(op.parameter)].state == Entry::State::done && ok;
    return ok;
  }

  bool compile_source(int i) {
    const ast::Expr& source = *entries_[static_cast<std::size_t>(i)].source;
    auto typed = compile_expression(
        source, [this](const ast::Expr& r) { return reference(r); }, errors_);
    Entry& e = entries_[static_cast<std::size_t>(i)];
    if (!typed.ok || e.state == Entry::State::failed) return false;
    e.parameter.expression = std::move(typed.expression);
    if (!e.dimension_known) {
      e.parameter.dimension = typed.free ? dim::none : typed.dimension;
    } else if (!typed.free && typed.dimension != e.parameter.dimension) {
      error(e.parameter.where, fmt::format("{} expects {}, got {}", describe_parameter(e.parameter, e.meta), with_article(e.parameter.dimension),
                                           with_article(typed.dimension)));
      return false;
    }
    return true;
  }

  const ast::Model& model_;
  const ModelLookup& lookup_;
  std::vector<Diagnostic>& errors_;
  std::size_t first_error_;
  ModelInfo info_;
  std::vector<Entry> entries_;
  std::map<std::string, int> index_;  // path -> entry
  std::vector<double> values_;
  std::vector<std::string> known_paths_;  // every path, for suggestions; filled on first use
  std::size_t expanded_ = 0;              // elements and parameters copied from instances
};

}  // namespace

ModelInfo build_model(const ast::Model& model, const ModelLookup& lookup, std::vector<Diagnostic>& errors) {
  return Builder(model, lookup, errors).run();
}

}  // namespace rheo::lang
