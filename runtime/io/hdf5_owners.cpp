#include "runtime/io/hdf5_owners.hpp"

#include "lang/text_encoding.hpp"

#include <fmt/format.h>

namespace rheo::runtime::hdf5 {
namespace {

// The first record walked downward: the innermost, where the fault was found.
herr_t take_first(unsigned n, const H5E_error2_t* record, void* out) {
  auto* text = static_cast<std::string*>(out);
  if (n == 0 && record && record->desc) *text = record->desc;
  return 0;
}

}  // namespace

void library() {
  static const bool quiet = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)quiet;
}

std::string last_error() {
  std::string text;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, take_first, &text);
  H5Eclear2(H5E_DEFAULT);
  return text;
}

void fail(const std::string& file, const char* call, const std::string& what) {
  const std::string detail = last_error();
  throw DataError(fmt::format("{}: error: HDF5 {} failed on {}{}", lang::printable(file), call, lang::printable(what),
                              detail.empty() ? "" : fmt::format(" ({})", lang::printable(detail))));
}

}  // namespace rheo::runtime::hdf5
