#include "runtime/diagnosis/element_text.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <initializer_list>
#include <stdexcept>

namespace rheo::runtime::diagnosis {
namespace {

struct Writer {
  const Network& network;
  double split;
  ElementText out;

  // The parameter at PATH, or -1.
  int find(const std::string& path) const {
    const auto& parameters = network.model().parameters;
    for (std::size_t i = 0; i < parameters.size(); ++i)
      if (parameters[i].path == path) return static_cast<int>(i);
    return -1;
  }
  // `KEY = VALUE UNIT [in [LO, HI]]` of the parameter at PATH (internal value / per_unit).
  std::optional<std::string> named(const lang::Element& e, const char* key, double per_unit, const char* unit) {
    const int i = find(e.path + "." + key);
    if (i < 0) return std::nullopt;
    const lang::Parameter& p = network.model().parameters[static_cast<std::size_t>(i)];
    const double value = network.parameter(i) / per_unit;
    if (!p.free) return fmt::format("{} = {:.12g} {}", key, value, unit);
    ++out.free;
    return fmt::format("{} = {:.12g} {} in [{:.9g}, {:.9g}]", key, value, unit, p.lower / per_unit, p.upper / per_unit);
  }
  // One cap both ways: split into fy_pos and fy_neg when asked.
  std::optional<std::string> cap(const lang::Element& e, std::size_t slot) {
    ++out.symmetric_caps;
    if (split == 0.0) return find(e.path + ".uy") >= 0 ? named(e, "uy", 1e-3, "um") : named(e, "fy", 1.0, "N");
    const int i = e.parameters[slot];
    const lang::Parameter& p = network.model().parameters[static_cast<std::size_t>(i)];
    const double fy = network.parameter(i);
    const double lo = p.free ? p.lower : fy / 1e3, hi = p.free ? p.upper : fy * 1e3;
    out.free += 2;
    return fmt::format("fy_pos = {:.12g} N in [{:.9g}, {:.9g}], fy_neg = {:.12g} N in [{:.9g}, {:.9g}]", fy * (1.0 + split), lo, hi,
                       fy * (1.0 - split), lo, hi);
  }
  bool leaf(const lang::Element& e, const char* kind, std::initializer_list<std::optional<std::string>> arguments, const std::string& indent) {
    std::vector<std::string> written;
    for (const auto& a : arguments) {
      if (!a) return false;
      written.push_back(*a);
    }
    out.lines.push_back(fmt::format("{}{} {} ({})", indent, kind, e.name, fmt::join(written, ", ")));
    return true;
  }
  bool write(const lang::Element& e, const std::string& indent) {
    using K = lang::ElementKind;
    switch (e.kind) {
      case K::spring: return leaf(e, "spring", {named(e, "k", 1.0, "N/mm")}, indent);
      case K::dashpot: return leaf(e, "dashpot", {named(e, "c", 1.0, "N*s/mm")}, indent);
      case K::inerter: return leaf(e, "inerter", {named(e, "b", 1e-3, "kg")}, indent);
      case K::maxwell:
        if (find(e.path + ".tau") >= 0) return leaf(e, "maxwell", {named(e, "k", 1.0, "N/mm"), named(e, "tau", 1e-3, "ms")}, indent);
        return leaf(e, "maxwell", {named(e, "k", 1.0, "N/mm"), named(e, "c", 1.0, "N*s/mm")}, indent);
      case K::friction:  // {k, fy} or {k, fy_pos, fy_neg}
        if (e.parameters.size() == 3)
          return leaf(e, "friction", {named(e, "k", 1.0, "N/mm"), named(e, "fy_pos", 1.0, "N"), named(e, "fy_neg", 1.0, "N")}, indent);
        return leaf(e, "friction", {named(e, "k", 1.0, "N/mm"), cap(e, 1)}, indent);
      case K::slider:  // {fy} or {fy_pos, fy_neg}
        if (e.parameters.size() == 2) return leaf(e, "slider", {named(e, "fy_pos", 1.0, "N"), named(e, "fy_neg", 1.0, "N")}, indent);
        return leaf(e, "slider", {cap(e, 0)}, indent);
      case K::gap: return leaf(e, "gap", {named(e, "width", 1.0, "mm"), named(e, "center", 1.0, "mm")}, indent);
      case K::yeoh: return leaf(e, "yeoh", {named(e, "D10", 1.0, "N/mm"), named(e, "D20", 1.0, "N/mm^3"), named(e, "D30", 1.0, "N/mm^5")}, indent);
      case K::poly_spring:
        return leaf(e, "poly_spring", {named(e, "k1", 1.0, "N/mm"), named(e, "k2", 1.0, "N/mm^2"), named(e, "k3", 1.0, "N/mm^3")}, indent);
      case K::parallel:
      case K::series:
        out.lines.push_back(fmt::format("{}{} {} {{", indent, lang::kind_word(e.kind), e.name));
        for (const lang::Element& child : e.children)
          if (!write(child, indent + "  ")) return false;
        out.lines.push_back(indent + "}");
        return true;
      case K::quadratic_dashpot:
      case K::bouc_wen:
      case K::springpot: return false;
    }
    return false;
  }
};

}  // namespace

std::optional<ElementText> element_text(const Network& network, const lang::Element& element, double split) {
  Writer w{network, split, {}};
  if (!w.write(element, "")) return std::nullopt;
  return w.out;
}

std::string joined(const ElementText& text) { return fmt::format("{}", fmt::join(text.lines, "\n")); }

const lang::Element& root_element(const Network& network, const std::string& name) {
  for (const lang::Element& e : network.model().root.children)
    if (e.name == name) return e;
  throw std::logic_error("diagnose: no root element " + name);
}

std::vector<double> play_biases(bool symmetric_drives) {
  return symmetric_drives ? std::vector<double>{0.0, 0.5} : std::vector<double>{-0.5, 0.0, 0.5};
}

std::vector<Trial> gapped_element_family(const Network& network, const std::vector<double>& half_widths, bool symmetric_drives) {
  std::vector<Trial> family;
  for (const lang::Element& e : network.model().root.children) {
    if (e.kind != lang::ElementKind::spring && e.kind != lang::ElementKind::maxwell && e.kind != lang::ElementKind::friction) continue;
    const auto text = element_text(network, e);
    if (!text) continue;
    const bool symmetric = e.kind != lang::ElementKind::friction || e.parameters.size() == 2;  // one cap both ways
    for (double half : half_widths)
      for (double bias : play_biases(symmetric_drives && symmetric)) {
        Trial t;
        t.effect = Effect::backlash, t.shape = Shape::gapped_element, t.slip = half, t.bias = bias;
        t.replaces = e.name, t.inner = joined(*text);
        family.push_back(t);
      }
  }
  return family;
}

std::vector<Trial> one_sided_family(const Network& network) {
  std::vector<Trial> family;
  for (const lang::Element& e : network.model().root.children) {
    const auto text = element_text(network, e);
    if (!text || text->symmetric_caps == 0) continue;
    for (double bias : {-0.5, -0.2, 0.2, 0.5}) {
      Trial t;
      t.effect = Effect::asymmetry, t.shape = Shape::one_sided_element, t.bias = bias, t.replaces = e.name,
      t.split_parameters = element_text(network, e, bias)->free - text->free;
      family.push_back(t);
    }
  }
  return family;
}

}  // namespace rheo::runtime::diagnosis
