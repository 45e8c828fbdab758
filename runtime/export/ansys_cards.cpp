#include "runtime/export/ansys_cards.hpp"

#include "runtime/core/errors.hpp"

#include <fmt/format.h>

namespace rheo::runtime::fe {
namespace {

[[noreturn]] void too_many_terms(const PronyCards& cards) {
  std::string chains;
  for (const auto& c : cards.springpots)
    chains += fmt::format("{}springpot '{}' ({}:{}:{}) {} modes over {:g} .. {:g} Hz", chains.empty() ? "" : ", ", c.path, c.where.file,
                          c.where.line, c.where.column, c.modes, c.f_low, c.f_high);
  const std::string prefix = cards.springpots.empty() ? "" : error_at(cards.springpots.front().where);
  throw ModelError(fmt::format("{}model '{}' makes {} Prony terms, and ANSYS's TB,PRONY takes at most {} pairs{}; {}", prefix, cards.model,
                               cards.terms.size(), kAnsysMaxPronyPairs, chains.empty() ? "" : fmt::format(" ({})", chains),
                               chains.empty() ? "merge Maxwell elements of close relaxation times, or export --abaqus"
                                              : "narrow the springpot bands f_low .. f_high (a chain has 4 modes per decade and 14 more), or "
                                                "export --abaqus, which takes them all"));
}

// The TB,PRONY table TBOPT with every term's (a_i, tau_i), three pairs a TBDATA command.
std::string prony_table(const PronyCards& cards, const char* option) {
  std::string out = fmt::format("TB,PRONY,RHEO_MAT,1,{},{}\n", cards.terms.size(), option);
  for (std::size_t i = 0; i < cards.terms.size(); i += 3) {
    out += fmt::format("TBDATA,{}", 2 * i + 1);
    for (std::size_t j = i; j < i + 3 && j < cards.terms.size(); ++j)
      out += fmt::format(",{},{}", card_number(cards.terms[j].ratio), card_number(cards.terms[j].relaxation_time));
    out += "\n";
  }
  return out;
}

}  // namespace

std::string ansys_material(const PronyCards& cards, const MaterialMapping& mapping, const CardSource& source) {
  if (cards.terms.size() > kAnsysMaxPronyPairs) too_many_terms(cards);
  std::string out = card_header(cards, mapping, source, "!", "ANSYS Mechanical APDL");
  out += "! Use: in /PREP7, /INPUT,'<this file>' (or paste it into a Mechanical command snippet and set RHEO_MAT = matid).\n";
  out += "! Commands: MP,EX and MP,PRXY: the instantaneous E_0, nu; TB,PRONY,MAT,1,N,SHEAR and ...,BULK with TBDATA pairs a_i,\n";
  out += "!   tau_i, the relative moduli to the instantaneous modulus (Command Reference, TB; Material Reference, viscoelasticity).\n";
  out += "RHEO_MAT = 1  ! the material number these commands define\n";
  out += fmt::format("MP,EX,RHEO_MAT,{}\n", card_number(young_modulus(cards.instantaneous, mapping)));
  out += fmt::format("MP,PRXY,RHEO_MAT,{}\n", card_number(mapping.poisson));
  if (cards.terms.empty()) return out;
  out += prony_table(cards, "SHEAR");
  out += prony_table(cards, "BULK");
  return out;
}

}  // namespace rheo::runtime::fe
