// What the Abaqus and ANSYS card files share: the isotropic reading of the 1-D modulus, the
// numbers, and the comment header that says what the cards are, in which units, for which
// elements, and where they come from.
#pragma once

#include "runtime/export/prony_cards.hpp"

#include <cstdint>
#include <string>
#include <string_view>

namespace rheo::runtime::fe {

// What the 1-D modulus M of the cards is in an isotropic 3-D material.
enum class ModulusKind : std::uint8_t {
  young,  // M = E (uniaxial stress: a tension or compression test, or no geometry)
  shear,  // M = G, E = 2 (1 + nu) G (a shear test: parallel plates, a shear sandwich)
};

struct MaterialMapping {
  ModulusKind modulus = ModulusKind::young;
  double poisson = 0.49;  // nu [-], 0 <= nu < 0.5: not in the 1-D model, an assumption the header states
};

// Young's modulus [MPa] of the 1-D modulus M [MPa] under MAPPING: M, or 2 (1 + nu) M.
double young_modulus(double modulus, const MaterialMapping& mapping);

// Where the cards come from, for the header.
struct CardSource {
  std::string source_file;   // the .rheo file as given
  std::string rheo_version;  // "0.1.0"
};

// A number as both codes read it back to the same double: the shortest round-trip digits, with
// a decimal point in the mantissa ("100." , "1.e-05", "0.25").
std::string card_number(double value);

// The header of a card file, every line starting with COMMENT ("**", "!"): source, units, the
// 1-D relaxation and complex modulus, the geometry or its absence, the 3-D reading, the elements
// behind each term, and what is left out. Ends with a newline.
std::string card_header(const PronyCards& cards, const MaterialMapping& mapping, const CardSource& source, std::string_view comment,
                        std::string_view code);

}  // namespace rheo::runtime::fe
