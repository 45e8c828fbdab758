// libFuzzer target: the input is a measured harmonic table (runtime/io/harmonic_data.hpp), read
// from memory as read_harmonic_data reads it from a file.
#include "documented_errors.hpp"
#include "runtime/io/harmonic_data.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  rheo::fuzz::expect_only_documented_errors([&] { (void)rheo::runtime::harmonic_data_from_table(rheo::runtime::parse_table("fuzz.csv", text)); });
  return 0;
}
