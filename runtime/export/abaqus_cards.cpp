#include "runtime/export/abaqus_cards.hpp"

#include <fmt/format.h>

#include <cctype>

namespace rheo::runtime::fe {

std::string abaqus_material(const PronyCards& cards, const MaterialMapping& mapping, const CardSource& source) {
  std::string out = card_header(cards, mapping, source, "**", "Abaqus");
  out += "** Use: *INCLUDE, INPUT=<this file> in the model data, and MATERIAL=<the name below> on a section.\n";
  out += "** Cards: *ELASTIC, MODULI=INSTANTANEOUS: E_0, nu (Keywords Reference, *ELASTIC); *VISCOELASTIC, TIME=PRONY: per term\n";
  out += "**   g_i, k_i, tau_i, the shear and bulk ratios to the instantaneous moduli (Keywords Reference, *VISCOELASTIC).\n";
  const bool letter = !cards.model.empty() && std::isalpha(static_cast<unsigned char>(cards.model.front()));
  out += fmt::format("*MATERIAL, NAME={}{}\n", letter ? "" : "M", cards.model);
  out += cards.terms.empty() ? "*ELASTIC\n" : "*ELASTIC, MODULI=INSTANTANEOUS\n";
  out += fmt::format("{}, {}\n", card_number(young_modulus(cards.instantaneous, mapping)), card_number(mapping.poisson));
  if (cards.terms.empty()) return out;
  out += "*VISCOELASTIC, TIME=PRONY\n";
  for (const PronyTerm& t : cards.terms) out += fmt::format("{0}, {0}, {1}\n", card_number(t.ratio), card_number(t.relaxation_time));
  return out;
}

}  // namespace rheo::runtime::fe
