// The numbers of the cards read back to the same double, in the forms Abaqus and APDL read
// (a decimal point in the mantissa); the 3-D reading of the 1-D modulus.
#include "runtime/export/card_text.hpp"

#include <doctest/doctest.h>

#include <cstdlib>
#include <string>

namespace card_text_test {

using namespace rheo;
namespace fe = runtime::fe;

TEST_CASE("card numbers: a decimal point in the mantissa, and the same double read back") {
  CHECK(fe::card_number(100.0) == "100.");
  CHECK(fe::card_number(1e-5) == "1.e-05");
  CHECK(fe::card_number(0.25) == "0.25");
  CHECK(fe::card_number(-3e20) == "-3.e+20");
  CHECK(fe::card_number(0.0) == "0.");
  for (double v : {1.0 / 3.0, 6.02214076e23, 1e-300, 123456.789, 0.038461538461538464, 9.999999999999998e-12})
    CHECK(std::strtod(fe::card_number(v).c_str(), nullptr) == v);
  CHECK_THROWS_AS(fe::card_number(1.0 / 0.0), std::logic_error);
}

TEST_CASE("card material mapping: M is E, or G with E = 2 (1 + nu) G") {
  CHECK(fe::young_modulus(10.0, {fe::ModulusKind::young, 0.3}) == 10.0);
  CHECK(fe::young_modulus(10.0, {fe::ModulusKind::shear, 0.5}) == 30.0);
}

}  // namespace card_text_test
