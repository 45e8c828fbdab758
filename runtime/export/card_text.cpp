#include "runtime/export/card_text.hpp"

#include "lang/text_encoding.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rheo::runtime::fe {
namespace {

std::string at(const lang::SourceLocation& where) { return fmt::format("{}:{}:{}", lang::printable(where.file, 400), where.line, where.column); }

// "term 3" or "terms 3-26" (1-based).
std::string term_range(std::size_t first, std::size_t count) {
  return count == 1 ? fmt::format("term {}", first + 1) : fmt::format("terms {}-{}", first + 1, first + count);
}

}  // namespace

double young_modulus(double modulus, const MaterialMapping& mapping) {
  return mapping.modulus == ModulusKind::young ? modulus : 2.0 * (1.0 + mapping.poisson) * modulus;
}

std::string card_number(double value) {
  if (!std::isfinite(value)) throw std::logic_error("a card number must be finite");
  const std::string text = fmt::format("{}", value);
  const std::size_t exponent = std::min(text.find('e'), text.size());
  if (text.substr(0, exponent).find('.') != std::string::npos) return text;
  return fmt::format("{}.{}", text.substr(0, exponent), text.substr(exponent));
}

std::string card_header(const PronyCards& cards, const MaterialMapping& mapping, const CardSource& source, std::string_view comment,
                        std::string_view code) {
  std::string out;
  const auto line = [&](const std::string& text) { out += fmt::format("{} {}\n", comment, text); };
  line(fmt::format("{} material of model '{}' from {}, written by rheo {} (rheo export).", code, cards.model,
                   lang::printable(source.source_file, 400), source.rheo_version));
  line("Linear viscoelastic material: the model's generalised Maxwell (Prony) series, for continuum elements (solids, shells,");
  line("  membranes). Connector and spring elements (Abaqus *CONNECTOR ELASTICITY, ANSYS COMBIN14) take a stiffness and a");
  line("  damping, not a relaxation function: one Maxwell arm would be two of them in series with a node between.");
  line("Units: N, mm, s. Moduli in MPa (N/mm^2), relaxation times tau_i in s.");
  line("1-D relaxation modulus M(t) = M_0 (1 - sum_i r_i (1 - exp(-t/tau_i))), r_i the ratios below, and at w = 2 pi f");
  line("  storage M'(w) = M_inf + M_0 sum_i r_i w^2 tau_i^2 / (1 + w^2 tau_i^2), loss M''(w) = M_0 sum_i r_i w tau_i / (1 + w^2 tau_i^2):");
  line(fmt::format("  M_0 = {} MPa (instantaneous, t = 0), M_inf = {} MPa (long-term, t -> inf), {} term(s).", cards.instantaneous, cards.long_term,
                   cards.terms.size()));
  if (cards.geometry) {
    const Geometry& g = *cards.geometry;
    line(fmt::format("Specimen geometry from {}: area A = {} mm^2, height h = {} mm. M = K h / A, K the model's stiffness", g.source, g.area,
                     g.height));
    line("  [N/mm]: stress F/A over strain u/h. A part of this material loaded as the specimen was has the model's stiffness K = M A / h.");
  } else {
    line("No specimen geometry (no data line of the model's fit block gives area and height, and no --area/--height): M is the");
    line("  model's stiffness K in N/mm read as MPa, the material of a unit cube. A bar of it with cross-section A [mm^2] and");
    line("  length L [mm] in uniaxial stress has the stiffness M A / L: with A / L = 1 mm it gives the model's force F = K u.");
  }
  if (mapping.modulus == ModulusKind::young)
    line(fmt::format("Isotropic 3-D reading (--modulus young): M is Young's modulus E; E_0 = M_0 = {} MPa.",
                     young_modulus(cards.instantaneous, mapping)));
  else
    line(fmt::format("Isotropic 3-D reading (--modulus shear): M is the shear modulus G; E_0 = 2 (1 + nu) M_0 = {} MPa.",
                     young_modulus(cards.instantaneous, mapping)));
  line(fmt::format("  Poisson's ratio nu = {} is an assumption, not from the 1-D model (--poisson). Bulk and shear relax alike", mapping.poisson));
  line("  (bulk ratios = shear ratios), so nu is constant in time and E(t) and G(t) = E(t) / (2 (1 + nu)) follow M(t) exactly:");
  line("  uniaxial stress and simple shear reproduce the model. For a rubber whose bulk response is elastic, set the bulk ratios");
  line("  to 0: the shear response stays exact.");
  line("Elements:");
  for (const std::string& spring : cards.springs) line(fmt::format("  spring {} -> M_inf", spring));
  for (std::size_t i = 0; i < cards.terms.size();) {
    std::size_t n = 1;
    while (i + n < cards.terms.size() && cards.terms[i + n].element == cards.terms[i].element) ++n;
    const PronyTerm& t = cards.terms[i];
    const SpringpotChainNote* chain = nullptr;
    for (const auto& c : cards.springpots)
      if (c.path == t.element) chain = &c;
    if (chain)
      line(fmt::format("  springpot {} ({}) -> {}: rheo's Maxwell chain of it, {} modes standing for k (i w tau)^alpha over {:g} .. {:g} Hz",
                       t.element, at(t.where), term_range(i, n), chain->modes, chain->f_low, chain->f_high));
    else line(fmt::format("  Maxwell element {} ({}) -> {}", t.element, at(t.where), term_range(i, n)));
    i += n;
  }
  if (!cards.springpots.empty())
    line("  (the chain is what rheo simulates: within its band |K*| and the phase follow the springpot within 5e-4 and 0.02 deg)");
  for (const LeftOutBranch& b : cards.left_out)
    line(fmt::format("LEFT OUT (--leave-out): {} {} ({}); these cards lack its force.", lang::kind_word(b.kind), b.path, at(b.where)));
  if (cards.long_term == 0.0 && !cards.terms.empty())
    line("No spring: the material relaxes completely (M_inf = 0, the ratios sum to 1); some procedures need a long-term modulus.");
  return out;
}

}  // namespace rheo::runtime::fe
