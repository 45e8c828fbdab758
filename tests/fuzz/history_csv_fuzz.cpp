// libFuzzer target: the input is a displacement history table (runtime/io/history_csv.hpp), read
// from memory into a drive as `history file = ...` reads it from a file.
#include "documented_errors.hpp"
#include "runtime/io/history_csv.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  rheo::fuzz::expect_only_documented_errors([&] { (void)rheo::runtime::drive_from_table(rheo::runtime::parse_table("fuzz.csv", text)); });
  return 0;
}
