// Cells read as numbers: exactly strtod's double (both are correctly rounded; strtod is the
// independent reference), a '+' sign, a decimal comma, long cells, and what is not a number.
#include "runtime/io/cell_number.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <clocale>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>

namespace cell_number_test {

using namespace rheo::runtime;

TEST_CASE("a cell reads as the double strtod reads, bit for bit, on random decimal text") {
  std::setlocale(LC_NUMERIC, "C");
  std::mt19937_64 random(28);
  std::size_t mismatches = 0;
  for (int k = 0; k < 200000; ++k) {
    std::string whole, fraction;
    const int digits = 1 + static_cast<int>(random() % 25);
    for (int d = 0; d < digits; ++d) whole += static_cast<char>('0' + random() % 10);
    for (int d = 0, n = random() % 2 ? static_cast<int>(random() % 20) : -1; d < n; ++d) fraction += static_cast<char>('0' + random() % 10);
    std::string text = fmt::format("{}{}{}{}", random() % 2 ? "-" : "", whole, fraction.empty() && random() % 2 ? "" : ".", fraction);
    if (random() % 3 == 0) text += fmt::format("e{}", static_cast<int>(random() % 640) - 330);
    double got = 0.0;
    const CellNumber read = read_cell_number(text, false, got);
    const double want = std::strtod(text.c_str(), nullptr);
    if (read == CellNumber::out_of_range) {
      mismatches += std::isfinite(want) && want != 0.0 && std::abs(want) > 1e-300;  // strtod: inf, or an underflow to 0 or a subnormal
      continue;
    }
    mismatches += read != CellNumber::number || std::memcmp(&got, &want, sizeof got) != 0;
  }
  CHECK(mismatches == 0);
}

TEST_CASE("a leading plus, a decimal comma where the layout has one, and cells that are not numbers") {
  double v = 0.0;
  CHECK(read_cell_number("+2.5", false, v) == CellNumber::number);
  CHECK(v == 2.5);
  CHECK(read_cell_number("1,25", true, v) == CellNumber::number);
  CHECK(v == 1.25);
  CHECK(read_cell_number("1,25", false, v) == CellNumber::not_a_number);
  const std::string long_cell = "0," + std::string(80, '5');  // longer than the 64-byte copy
  CHECK(read_cell_number(long_cell, true, v) == CellNumber::number);
  CHECK(v == std::strtod(("0." + std::string(80, '5')).c_str(), nullptr));
  CHECK(read_cell_number("", false, v) == CellNumber::empty);
  CHECK(read_cell_number("+", false, v) == CellNumber::empty);
  CHECK(read_cell_number("++1", false, v) == CellNumber::not_a_number);
  CHECK(read_cell_number("1.5 mm", false, v) == CellNumber::not_a_number);
  CHECK(read_cell_number("1e400", false, v) == CellNumber::out_of_range);
  CHECK(read_cell_number("inf", false, v) == CellNumber::number);
  CHECK(std::isinf(v));
  CHECK(cell_as_read("+1,5", true) == "1.5");
  CHECK(cell_as_read("+1,5", false) == "1,5");
}

}  // namespace cell_number_test
