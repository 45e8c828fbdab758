#include "runtime/io/matlab_file.hpp"

#include "lang/text_encoding.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/io/hdf5_owners.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <fstream>

namespace rheo::runtime {
namespace {

constexpr std::array<std::string_view, 10> kNumeric{"double", "single", "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64"};

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return text;
}

// "FILE: error: PATH (ROLE) WHAT".
[[noreturn]] void refuse(const std::string& file, const std::string& path, const std::string& role_text, const std::string& what) {
  throw DataError(fmt::format("{}: error: {} ({}) {}", lang::printable(file), lang::printable(path), role_text, what));
}

// The variable's MATLAB name for advice: "/rig/t" -> "rig.t".
std::string matlab_name(const std::string& path) {
  std::string name = path.starts_with('/') ? path.substr(1) : path;
  std::replace(name.begin(), name.end(), '/', '.');
  return lang::printable(name);
}

}  // namespace

bool is_matlab_name(const std::string& path) { return lower(path).ends_with(".mat"); }

MatHeader matlab_header(std::string_view start) {
  if (start.starts_with("MATLAB 5.0 MAT-file")) return MatHeader::v5;
  if (start.starts_with("MATLAB 7.3 MAT-file")) return MatHeader::v73;
  return MatHeader::none;
}

void refuse_non_hdf5_matlab(const std::string& file) {
  std::string start(128, '\0');
  {
    std::ifstream in(file, std::ios::binary);
    in.read(start.data(), static_cast<std::streamsize>(start.size()));
    start.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  }
  const std::string shown = lang::printable(file);
  if (matlab_header(start) == MatHeader::v5)
    throw DataError(
        fmt::format("{}: error: this is a MATLAB v5/v7 MAT-file (the default of save), which rheo cannot read; re-save it as v7.3 "
                    "(an HDF5 file) in MATLAB, e.g. save('{}', 't', 'x', 'F', '-v7.3'), or export the history as a CSV table",
                    shown, lang::printable(std::string(std::string_view(file).substr(file.find_last_of('/') + 1)))));
  throw DataError(
      fmt::format("{}: error: this is not a MATLAB v7.3 MAT-file (rheo reads a file named .mat as one, an HDF5 file); re-save it in "
                  "MATLAB with save(..., '-v7.3'), or export the history as a CSV table",
                  shown));
}

std::string matlab_field_path(const std::string& file, const std::string& path) {
  if (!is_matlab_name(file) || path.find('/') != std::string::npos) return path;
  std::string out = path;
  std::replace(out.begin(), out.end(), '.', '/');
  return out;
}

std::optional<std::string> matlab_class(hid_t object, const std::string& file, const std::string& path) {
  return hdf5::string_attribute(object, "MATLAB_class", file, path, "MATLAB writes it as one; save the file again from MATLAB");
}

void check_matlab_dataset(hid_t dataset, const std::string& file, const std::string& path, const std::string& role_text) {
  const auto type_name = matlab_class(dataset, file, path);
  if (!type_name) return;
  const std::string& c = *type_name;
  const std::string save = fmt::format("save the {} as a numeric array (double) in MATLAB", role_text);
  const htri_t empty = H5Aexists(dataset, "MATLAB_empty");
  hdf5::check(empty, file, "H5Aexists", path);
  if (empty > 0)
    refuse(file, path, role_text,
           fmt::format("is an empty MATLAB array ({}); a history needs its samples: save the variable that holds them", lang::printable(c)));
  if (c == "char")
    refuse(file, path, role_text,
           fmt::format("is a MATLAB char array (text), not numbers; {}, e.g. {} = str2double({})", save, matlab_name(path), matlab_name(path)));
  if (c == "logical") refuse(file, path, role_text, fmt::format("is a MATLAB logical array (true/false), not measurements; {}", save));
  if (c == "cell")
    refuse(file, path, role_text, fmt::format("is a MATLAB cell array; {}, e.g. {} = cell2mat({})", save, matlab_name(path), matlab_name(path)));
  if (std::find(kNumeric.begin(), kNumeric.end(), c) == kNumeric.end())
    refuse(file, path, role_text,
           fmt::format("is a MATLAB {} {}, not a numeric array; {}", lang::printable(c), c == "struct" ? "array" : "object", save));
  hdf5::Datatype type(H5Dget_type(dataset), file, "H5Dget_type", path);
  if (H5Tget_class(type.get()) == H5T_COMPOUND)
    refuse(file, path, role_text,
           fmt::format("holds complex numbers; rheo reads real ones: save the real part, e.g. {} = real({})", matlab_name(path), matlab_name(path)));
}

void refuse_matlab_group(hid_t group, const std::string& file, const std::string& path, const std::string& role_text, const std::string& holds) {
  const auto type_name = matlab_class(group, file, path);
  if (!type_name) return;
  const htri_t sparse = H5Aexists(group, "MATLAB_sparse");
  hdf5::check(sparse, file, "H5Aexists", path);
  if (sparse > 0)
    refuse(file, path, role_text, fmt::format("is a MATLAB sparse matrix; save it full, e.g. {} = full({})", matlab_name(path), matlab_name(path)));
  if (*type_name == "struct")
    refuse(file, path, role_text,
           fmt::format("is a MATLAB struct, not an array; name one of its fields, e.g. columns = \"{} = {}.field\": it holds {}", role_text,
                       matlab_name(path), holds));
  refuse(file, path, role_text,
         fmt::format("is a MATLAB {} object, not a numeric array; save the {} as a numeric array (double) in MATLAB", lang::printable(*type_name),
                     role_text));
}

}  // namespace rheo::runtime
