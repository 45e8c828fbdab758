// A model's linear viscoelastic part as a Prony series (the generalised Maxwell model), the data
// behind the finite-element material cards (abaqus_cards.hpp, ansys_cards.hpp).
//
// The model's branches acting in parallel (its body, and parallel blocks in it) map to
//   spring k                         the long-term stiffness:   K_inf += k
//   maxwell k, c (tau = c/k)         one term:                  K_i = k, tau_i = c/k
//   series { spring k  dashpot c }   one term, the same Maxwell element
//   springpot                        one term per mode of rheo's Maxwell chain (the chain every
//                                    integrator steps, runtime/network/springpot.hpp), K_j, c_j/K_j
// so that the relaxation stiffness and the complex stiffness are
//   K(t)  = K_inf + sum_i K_i e^{-t/tau_i},  K_0 = K(0) = K_inf + sum_i K_i,
//   K*(w) = K_inf + sum_i K_i i w tau_i / (1 + i w tau_i)            (eqs. 2.3, 5.11)
// exactly those of `rheo simulate`'s harmonic closed form. The cards give it normalised, as FE
// codes take it: r_i = K_i / K_0 (Abaqus g_i, ANSYS alpha_i) and the instantaneous modulus.
//
// With a specimen's geometry (a data line's area A [mm^2] and height h [mm], docs/data-formats.md)
// the stiffness becomes a modulus, M = K h / A [MPa = N/mm^2] (stress F/A over strain u/h);
// without it the "modulus" is the stiffness in N/mm read as MPa: the material of a unit cube
// (A = 1 mm^2, h = 1 mm).
//
// Every other branch has no Prony counterpart (a yeoh, poly_spring, friction, slider, gap,
// bouc_wen, quadratic_dashpot or inerter anywhere in it, a dashpot acting in parallel, a series
// block other than one spring and one dashpot): ModelError naming each such element at its
// file:line:col, unless its branch is left out by name, which the cards then report.
#pragma once

#include "lang/model.hpp"
#include "runtime/network/network.hpp"

#include <optional>
#include <string>
#include <vector>

namespace rheo::runtime::fe {

// The specimen the modulus is read on: modulus = stiffness * height / area.
struct Geometry {
  double area = 0.0;    // mm^2
  double height = 0.0;  // mm
  std::string source;   // where it comes from, for the file's header ("m.rheo:7:8", "--area/--height")
};

struct PronyTerm {
  double ratio = 0.0;            // r_i = K_i / K_0 [-]
  double relaxation_time = 0.0;  // tau_i [s]
  std::string element;           // the element path it comes from
  lang::SourceLocation where;    // of that element
};

// A springpot exported as its Maxwell chain.
struct SpringpotChainNote {
  std::string path;
  int modes = 0;                     // terms it adds
  double f_low = 0.0, f_high = 0.0;  // Hz, the band where the chain follows k (i w tau)^alpha
  lang::SourceLocation where;
};

// A branch of the parallel block left out by name (--leave-out): the cards lack its force.
struct LeftOutBranch {
  std::string path;
  lang::ElementKind kind;
  lang::SourceLocation where;
};

struct PronyCards {
  std::string model;
  std::optional<Geometry> geometry;  // nullopt: stiffness terms (N/mm read as MPa)
  double instantaneous = 0.0;        // M_0 = K_0 h / A [MPa], or K_0 [N/mm] without geometry
  double long_term = 0.0;            // M_inf = K_inf h / A, or K_inf
  std::vector<PronyTerm> terms;      // in source order; a springpot's modes by rising tau
  std::vector<std::string> springs;  // paths of the springs making K_inf
  std::vector<SpringpotChainNote> springpots;
  std::vector<LeftOutBranch> left_out;
};

// The Prony series of NETWORK's model (its parameter values, the springpot chains as compiled).
// LEAVE_OUT: paths of branches of the parallel block to leave out; a path that names no element,
// or one inside a series block, is a UsageError saying what to name. ModelError listing every
// element with no Prony counterpart (above); UsageError when nothing is left.
PronyCards prony_cards(const Network& network, const std::optional<Geometry>& geometry, const std::vector<std::string>& leave_out);

}  // namespace rheo::runtime::fe
