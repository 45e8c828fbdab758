// The Prony series as ANSYS Mechanical APDL commands (a macro for /INPUT or a command snippet):
//   RHEO_MAT = 1                              the material number (a parameter: change it once)
//   MP,EX,RHEO_MAT,E_0   MP,PRXY,RHEO_MAT,nu  the instantaneous elastic constants
//   TB,PRONY,RHEO_MAT,1,N,SHEAR               N pairs for the shear relaxation,
//   TBDATA,1,a_1,tau_1,a_2,tau_2,a_3,tau_3    six constants a command, STLOC 1, 7, 13, ...
//   TB,PRONY,RHEO_MAT,1,N,BULK                the same pairs for the bulk relaxation
// Command Reference, TB: Lab = PRONY, NTEMP = 1, NPTS = N pairs, TBOPT = SHEAR or BULK; TBDATA,
// STLOC, C1..C6. Material Reference, "Viscoelastic Material Constants" and Theory Reference,
// viscoelasticity: G(t) = G_0 (a_inf + sum_i a_i e^{-t/tau_i}), a_i the relative moduli to the
// instantaneous modulus G_0 (from MP: EX, PRXY), a_inf = 1 - sum_i a_i, and likewise K(t); so
// a_i = r_i of prony_cards.hpp. A table holds at most 100 pairs.
#pragma once

#include "runtime/export/card_text.hpp"

#include <string>

namespace rheo::runtime::fe {

inline constexpr std::size_t kAnsysMaxPronyPairs = 100;

// The .mac text: card_header() as "!" comments, then the commands above (MP alone for a model
// without Maxwell elements). ModelError, naming the springpots that make them, when there are
// more than kAnsysMaxPronyPairs terms.
std::string ansys_material(const PronyCards& cards, const MaterialMapping& mapping, const CardSource& source);

}  // namespace rheo::runtime::fe
