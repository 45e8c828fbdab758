#include "runtime/io/cell_number.hpp"

#include <algorithm>
#include <charconv>
#include <system_error>

namespace rheo::runtime {

CellNumber read_cell_number(std::string_view cell, bool decimal_comma, double& value) {
  if (!cell.empty() && cell.front() == '+') cell.remove_prefix(1);
  if (cell.empty()) return CellNumber::empty;
  char buffer[64];
  std::string long_cell;
  if (decimal_comma && cell.find(',') != std::string_view::npos) {
    char* first = buffer;
    if (cell.size() > sizeof buffer) {
      long_cell.assign(cell);
      first = long_cell.data();
    } else {
      std::copy(cell.begin(), cell.end(), buffer);
    }
    std::replace(first, first + cell.size(), ',', '.');
    cell = std::string_view(first, cell.size());
  }
  double read = 0.0;
  const auto [end, error] = std::from_chars(cell.data(), cell.data() + cell.size(), read);
  if (end != cell.data() + cell.size() || (error != std::errc{} && error != std::errc::result_out_of_range)) return CellNumber::not_a_number;
  if (error == std::errc::result_out_of_range) return CellNumber::out_of_range;
  value = read;
  return CellNumber::number;
}

std::string cell_as_read(std::string_view cell, bool decimal_comma) {
  if (!cell.empty() && cell.front() == '+') cell.remove_prefix(1);
  std::string text(cell);
  if (decimal_comma) std::replace(text.begin(), text.end(), ',', '.');
  return text;
}

}  // namespace rheo::runtime
