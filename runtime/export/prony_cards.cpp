#include "runtime/export/prony_cards.hpp"

#include "lang/names.hpp"
#include "lang/text_encoding.hpp"
#include "runtime/core/errors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>

namespace rheo::runtime::fe {
namespace {

using lang::Element;
using lang::ElementKind;

// A block of one member acts as that member.
const Element& collapsed(const Element& e) {
  const Element* p = &e;
  while ((p->kind == ElementKind::parallel || p->kind == ElementKind::series) && p->children.size() == 1) p = &p->children.front();
  return *p;
}

// The members of a series block, nested series blocks spliced.
void series_members(const Element& block, std::vector<const Element*>& out) {
  for (const Element& child : block.children) {
    const Element& c = collapsed(child);
    if (c.kind == ElementKind::series) series_members(c, out);
    else out.push_back(&c);
  }
}

// Why an element has no Prony counterpart, completing "KIND 'PATH' ..."; empty for the linear
// leaves that have one in the right place (springs, dashpots, maxwell elements, springpots).
std::string no_counterpart(ElementKind kind) {
  switch (kind) {
    case ElementKind::yeoh: return "is a non-linear spring (F = 2 (D10 + 2 D20 e^2 + 3 D30 e^4) e), and a Prony series is linear";
    case ElementKind::poly_spring: return "is a non-linear spring (F = k1 e + k2 e^2 + k3 e^3), and a Prony series is linear";
    case ElementKind::friction:
    case ElementKind::slider:
    case ElementKind::bouc_wen: return "is rate-independent friction (hysteresis that does not fade with time), which a Prony series does not have";
    case ElementKind::gap: return "is free play, which a linear material does not have";
    case ElementKind::quadratic_dashpot: return "is a non-linear damper (F = cq |de/dt| de/dt), and a Prony series is linear";
    case ElementKind::inerter: return "is a mass (F = b d2e/dt2), which a material's relaxation function does not have";
    default: return "";
  }
}

struct Refusal {
  const Element* element;
  std::string reason;
  std::string branch;  // the path --leave-out takes
};

class Builder {
 public:
  Builder(const Network& network, const std::vector<std::string>& leave_out) : network_(network), leave_out_(leave_out.begin(), leave_out.end()) {}

  void branches_of(const Element& block) {
    for (const Element& child : block.children) {
      branches_.push_back(&child);
      if (left_out(child)) continue;
      const Element& b = collapsed(child);
      if (b.kind == ElementKind::parallel) branches_of(b);
      else branch(b, child.path);
    }
  }

  // The innermost branch of the parallel block whose subtree holds PATH; nullptr when none does.
  const Element* branch_holding(const std::string& path) const {
    for (auto b = branches_.rbegin(); b != branches_.rend(); ++b)
      if (holds(**b, path)) return *b;
    return nullptr;
  }

  PronyCards cards;
  std::vector<Refusal> refusals;
  std::vector<std::pair<double, double>> stiffness_and_tau;  // K_i [N/mm], tau_i [s], one per term
  double long_term_stiffness = 0.0;

 private:
  double value(const Element& e, std::size_t slot) const { return network_.parameter(e.parameters.at(slot)); }

  void term(double k, double c, const Element& e) {
    stiffness_and_tau.emplace_back(k, c / k);
    cards.terms.push_back({0.0, c / k, e.path, e.where});
  }

  void branch(const Element& b, const std::string& branch_path) {
    switch (b.kind) {
      case ElementKind::spring:
        long_term_stiffness += value(b, 0);
        cards.springs.push_back(b.path);
        return;
      case ElementKind::maxwell: term(value(b, 0), value(b, 1), b); return;
      case ElementKind::springpot: springpot(b); return;
      case ElementKind::dashpot:
        refusals.push_back({&b,
                            "acts in parallel, so its force c de/dt has no instantaneous limit, while a Prony series starts from a "
                            "finite instantaneous modulus; put a spring in series with it (a maxwell element with a relaxation "
                            "time beyond the slowest you care about)",
                            branch_path});
        return;
      case ElementKind::series: series(b, branch_path); return;
      default: refusals.push_back({&b, no_counterpart(b.kind), branch_path}); return;
    }
  }

  void series(const Element& block, const std::string& branch_path) {
    std::vector<const Element*> members;
    series_members(block, members);
    bool nonlinear = false;
    for (const Element* m : members) nonlinear |= nonlinear_inside(*m, branch_path);
    if (nonlinear) return;
    const auto count = [&](ElementKind kind) {
      return std::count_if(members.begin(), members.end(), [&](const Element* m) { return m->kind == kind; });
    };
    if (members.size() == 2 && count(ElementKind::spring) == 1 && count(ElementKind::dashpot) == 1) {
      const Element& spring = *(members[0]->kind == ElementKind::spring ? members[0] : members[1]);
      const Element& dashpot = *(members[0]->kind == ElementKind::dashpot ? members[0] : members[1]);
      term(value(spring, 0), value(dashpot, 0), spring);
      return;
    }
    refusals.push_back({&block,
                        "is a linear block, but not one spring and one dashpot in series (a Maxwell element); write its "
                        "relaxation as springs and maxwell elements side by side",
                        branch_path});
  }

  // Refuses every element with no counterpart below E (E included); true when there was one.
  bool nonlinear_inside(const Element& e, const std::string& branch_path) {
    if (e.kind == ElementKind::parallel || e.kind == ElementKind::series) {
      bool any = false;
      for (const Element& child : e.children) any |= nonlinear_inside(child, branch_path);
      return any;
    }
    const std::string reason = no_counterpart(e.kind);
    if (reason.empty()) return false;
    refusals.push_back({&e, reason, branch_path});
    return true;
  }

  void springpot(const Element& e) {
    const auto& chains = network_.topology().springpots;
    const auto chain = std::find_if(chains.begin(), chains.end(), [&](const SpringpotChain& c) { return c.path == e.path; });
    if (chain == chains.end()) throw std::logic_error(fmt::format("springpot '{}' has no compiled chain", e.path));
    for (int j = 0; j < chain->modes; ++j)
      term(network_.parameter(chain->first_derived + j), network_.parameter(chain->first_derived + chain->modes + j), e);
    cards.springpots.push_back({e.path, chain->modes, value(e, 3), value(e, 4), e.where});
  }

  // Whether BRANCH (or the member a one-member block stands for) is named by --leave-out.
  bool left_out(const Element& branch) {
    for (const Element* p = &branch;; p = &p->children.front()) {
      if (leave_out_.erase(p->path) > 0) {
        cards.left_out.push_back({p->path, p->kind, p->where});
        return true;
      }
      if (!((p->kind == ElementKind::parallel || p->kind == ElementKind::series) && p->children.size() == 1)) return false;
    }
  }

  static bool holds(const Element& e, const std::string& path) {
    if (e.path == path) return true;
    return std::any_of(e.children.begin(), e.children.end(), [&](const Element& c) { return holds(c, path); });
  }

  const Network& network_;
  std::set<std::string> leave_out_;       // not yet found; what remains is no branch
  std::vector<const Element*> branches_;  // every branch met, blocks spliced included

 public:
  const std::set<std::string>& unknown_leave_out() const { return leave_out_; }
};

void every_path(const Element& e, std::vector<std::string>& out) {
  if (!e.path.empty()) out.push_back(e.path);
  for (const Element& c : e.children) every_path(c, out);
}

[[noreturn]] void bad_leave_out(const Network& network, const Builder& builder, const std::string& path) {
  if (const Element* branch = builder.branch_holding(path))
    throw UsageError(
        fmt::format("--leave-out '{}': that element is part of {} '{}', a branch of model '{}''s parallel block; leave out the "
                    "whole branch: --leave-out {}",
                    lang::printable(path), lang::kind_word(branch->kind), branch->path, network.model().name, branch->path));
  std::vector<std::string> paths;
  every_path(network.model().root, paths);
  throw UsageError(fmt::format("--leave-out '{}': model '{}' has no element of that name;{} its elements are {}", lang::printable(path),
                               network.model().name, lang::did_you_mean(path, paths), lang::join(paths)));
}

std::string refusal_message(const Network& network, const Refusal& r) {
  return fmt::format("{}model '{}': {} '{}' {}; leave its branch out with --leave-out {} (the cards then lack its force)",
                     error_at(r.element->where), network.model().name, lang::kind_word(r.element->kind), r.element->path, r.reason, r.branch);
}

}  // namespace

PronyCards prony_cards(const Network& network, const std::optional<Geometry>& geometry, const std::vector<std::string>& leave_out) {
  Builder builder(network, leave_out);
  builder.branches_of(network.model().root);
  if (!builder.unknown_leave_out().empty()) bad_leave_out(network, builder, *builder.unknown_leave_out().begin());
  if (!builder.refusals.empty()) {
    std::string message;
    for (const Refusal& r : builder.refusals) message = fmt::format("{}{}\n", message, refusal_message(network, r));
    throw ModelError(
        fmt::format("{}rheo: model '{}' has no finite-element Prony series: a Prony series (Abaqus *VISCOELASTIC, ANSYS "
                    "TB,PRONY) holds springs, maxwell elements (or a spring and a dashpot in series) and springpots acting "
                    "side by side; export a model of those, or leave the others out",
                    message, network.model().name));
  }
  PronyCards cards = std::move(builder.cards);
  cards.model = network.model().name;
  double instantaneous = builder.long_term_stiffness;
  for (const auto& [k, tau] : builder.stiffness_and_tau) instantaneous += k;
  if (!(instantaneous > 0.0))
    throw UsageError(
        fmt::format("nothing of model '{}' is left to export: every branch of its parallel block is left out (--leave-out)", cards.model));
  for (std::size_t i = 0; i < cards.terms.size(); ++i) cards.terms[i].ratio = builder.stiffness_and_tau[i].first / instantaneous;
  const double scale = geometry ? geometry->height / geometry->area : 1.0;
  cards.geometry = geometry;
  cards.instantaneous = instantaneous * scale;
  cards.long_term = builder.long_term_stiffness * scale;
  return cards;
}

}  // namespace rheo::runtime::fe
