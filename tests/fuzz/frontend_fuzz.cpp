// libFuzzer target: the input is a .rheo source file, run through what `rheo check` does
// (cli/check_command.cpp) minus printing: parse, resolve imports, check, and compile
// every model to a network.
#include "documented_errors.hpp"
#include "lang/frontend.hpp"
#include "runtime/network/network.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  rheo::fuzz::expect_only_documented_errors([&] {
    const rheo::lang::Program program = rheo::lang::compile_source("fuzz.rheo", text);
    for (const auto& model : program.models) (void)rheo::runtime::Network::compile(model);
  });
  return 0;
}
