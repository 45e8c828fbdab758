#include "runtime/io/hdf5_owners.hpp"

#include "lang/text_encoding.hpp"

#include <fmt/format.h>

#include <vector>

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


std::optional<std::string> string_attribute(hid_t object, const char* name, const std::string& file, const std::string& path,
                                            const std::string& advice) {
  const htri_t has = H5Aexists(object, name);
  check(has, file, "H5Aexists", path);
  if (has == 0) return std::nullopt;
  const std::string what = fmt::format("the '{}' attribute of {}", name, path);
  Attribute attribute(H5Aopen(object, name, H5P_DEFAULT), file, "H5Aopen", what);
  Datatype type(H5Aget_type(attribute.get()), file, "H5Aget_type", what);
  Dataspace space(H5Aget_space(attribute.get()), file, "H5Aget_space", what);
  const hssize_t points = H5Sget_simple_extent_npoints(space.get());
  if (H5Tget_class(type.get()) != H5T_STRING || points != 1)
    throw DataError(fmt::format("{}: error: {} is not a string; {}", lang::printable(file), lang::printable(what), advice));
  Datatype memory(H5Tcopy(H5T_C_S1), file, "H5Tcopy", what);
  check(H5Tset_cset(memory.get(), H5Tget_cset(type.get())), file, "H5Tset_cset", what);
  const htri_t variable = H5Tis_variable_str(type.get());
  check(variable, file, "H5Tis_variable_str", what);
  std::string text;
  if (variable > 0) {
    check(H5Tset_size(memory.get(), H5T_VARIABLE), file, "H5Tset_size", what);
    char* value = nullptr;
    check(H5Aread(attribute.get(), memory.get(), &value), file, "H5Aread", what);
    if (value) text = value;
    H5free_memory(value);
  } else {
    const std::size_t size = H5Tget_size(type.get());
    std::vector<char> value(size + 1, '\0');  // a null-padded string of SIZE bytes keeps them all
    check(H5Tset_size(memory.get(), size + 1), file, "H5Tset_size", what);
    check(H5Aread(attribute.get(), memory.get(), value.data()), file, "H5Aread", what);
    text = value.data();
  }
  while (!text.empty() && (text.back() == ' ' || text.back() == '\0')) text.pop_back();
  return text;
}

}  // namespace rheo::runtime::hdf5
