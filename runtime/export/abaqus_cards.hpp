// The Prony series as an Abaqus material (an .inp fragment for *INCLUDE):
//   *MATERIAL, NAME=<model>
//   *ELASTIC, MODULI=INSTANTANEOUS          E_0, nu
//   *VISCOELASTIC, TIME=PRONY               g_i, k_i, tau_i   (one data line per term)
// Abaqus Keywords Reference, *ELASTIC: MODULI=INSTANTANEOUS says the elastic constants are the
// instantaneous ones (default LONG TERM), and applies only with *VISCOELASTIC. *VISCOELASTIC,
// TIME=PRONY: each data line gives g_i^P, k_i^P (the shear and bulk relaxation modulus ratios)
// and tau_i. Analysis User's Guide, "Time domain viscoelasticity": g_R(t) = G_R(t) / G_0 =
// 1 - sum_i g_i^P (1 - e^{-t/tau_i}), G_0 = G_R(0) the instantaneous shear modulus, and likewise
// k_R(t) for the bulk modulus; so g_i = k_i = r_i of prony_cards.hpp. A model without Maxwell
// elements is written as *ELASTIC alone (no MODULI, which needs *VISCOELASTIC).
#pragma once

#include "runtime/export/card_text.hpp"

#include <string>

namespace rheo::runtime::fe {

// The .inp text: card_header() as "**" comments, then the cards above. The material is named
// after the model (prefixed 'M' unless it starts with a letter, as Abaqus names must).
std::string abaqus_material(const PronyCards& cards, const MaterialMapping& mapping, const CardSource& source);

}  // namespace rheo::runtime::fe
