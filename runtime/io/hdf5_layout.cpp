#include "runtime/io/hdf5_layout.hpp"

#include "lang/text_encoding.hpp"
#include "lang/units.hpp"
#include "runtime/io/matlab_file.hpp"

#include <fmt/format.h>

#include <memory>
#include <optional>
#include <utility>

namespace rheo::runtime {
namespace {

// "/rig/t [ms]": the path and the unit written after it (nullopt: none written).
std::pair<std::string, std::optional<std::string>> path_and_unit(const std::string& named) {
  const auto open = named.rfind('[');
  if (named.empty() || named.back() != ']' || open == std::string::npos) return {named, std::nullopt};
  std::string path = named.substr(0, open);
  while (!path.empty() && (path.back() == ' ' || path.back() == '\t')) path.pop_back();
  return {path, named.substr(open + 1, named.size() - open - 2)};
}

std::string absolute(const std::string& path) { return path.starts_with('/') ? path : "/" + path; }

const std::string kUnitAdvice = "write the unit as one string, e.g. \"mm\"";

herr_t collect_name(hid_t, const char* name, const H5L_info_t*, void* out) {
  static_cast<std::vector<std::string>*>(out)->emplace_back(name);
  return 0;
}

// The names GROUP holds, for messages; not MATLAB's own groups of a .mat file (#refs#, the data
// of its cell arrays, and #subsystem#, of its objects).
std::vector<std::string> members(hid_t group, const std::string& file, const std::string& group_path) {
  std::vector<std::string> names;
  hdf5::check(H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_name, &names), file, "H5Literate", group_path);
  std::erase_if(names, [](const std::string& name) { return name == "#refs#" || name == "#subsystem#"; });
  return names;
}

std::string listed(const std::vector<std::string>& names) {
  if (names.empty()) return "nothing";
  std::string out;
  for (std::size_t i = 0; i < names.size() && i < 20; ++i) out += (i ? ", " : "") + lang::printable(names[i]);
  if (names.size() > 20) out += fmt::format(" and {} more", names.size() - 20);
  return out;
}

// The type of the object at PATH: H5I_DATASET, H5I_GROUP, ...
H5I_type_t object_type(hid_t file, const std::string& path, const std::string& file_name) {
  const hid_t object = H5Oopen(file, path.c_str(), H5P_DEFAULT);
  if (object < 0) hdf5::fail(file_name, "H5Oopen", path);
  const H5I_type_t type = H5Iget_type(object);
  H5Oclose(object);
  return type;
}

// Checks that PATH (absolute), which READING names for ROLE_TEXT, is a dataset: each group on
// the way, then the dataset; the first that is missing is named with what its group holds.
void check_named_path(hid_t file_id, const std::string& file, const std::string& dataset_path, const std::string& role_text) {
  const std::string shown = lang::printable(file);
  std::string at;
  for (std::size_t from = 1;;) {
    const auto slash = dataset_path.find('/', from);
    const std::string next = dataset_path.substr(0, slash);
    const std::string parent = at.empty() ? "/" : at;
    const htri_t exists = H5Lexists(file_id, next.c_str(), H5P_DEFAULT);
    hdf5::check(exists, file, "H5Lexists", next);
    if (exists == 0) {
      hdf5::Group group(H5Gopen2(file_id, parent.c_str(), H5P_DEFAULT), file, "H5Gopen2", parent);
      throw DataError(fmt::format("{}: error: no dataset {} for {}: there is no {}; {} holds {}", shown, lang::printable(dataset_path), role_text,
                                  lang::printable(next), parent == "/" ? "the root group" : lang::printable(parent),
                                  listed(members(group.get(), file, parent))));
    }
    const H5I_type_t type = object_type(file_id, next, file);
    if (slash == std::string::npos) {
      if (type == H5I_GROUP) {
        hdf5::Group group(H5Gopen2(file_id, next.c_str(), H5P_DEFAULT), file, "H5Gopen2", next);
        refuse_matlab_group(group.get(), file, next, role_text, listed(members(group.get(), file, next)));
        throw DataError(fmt::format("{}: error: {} ({}) is a group, not a dataset; name a dataset in it: it holds {}", shown, lang::printable(next),
                                    role_text, listed(members(group.get(), file, next))));
      }
      if (type != H5I_DATASET)
        throw DataError(fmt::format("{}: error: {} ({}) is not a dataset; name the dataset that holds the {}", shown, lang::printable(next),
                                    role_text, role_text));
      return;
    }
    if (type != H5I_GROUP)
      throw DataError(fmt::format("{}: error: no dataset {} for {}: {} is not a group", shown, lang::printable(dataset_path), role_text,
                                  lang::printable(next)));
    at = next;
    from = slash + 1;
  }
}

// The dataset at PATH for ROLE, open and checked; UNIT: the one written on the line. NAMING: a
// `columns` setting naming every role's dataset with a unit, for the advice on a MATLAB variable
// without one.
Hdf5Column open_column(hid_t file_id, const std::string& file, Role role, const std::string& path, std::optional<std::string> unit,
                       const std::string& naming) {
  const std::string shown = lang::printable(file), role_text(role_name(role));
  Hdf5Column column;
  column.role = role;
  column.path = path;
  const std::string& ds = column.path;
  column.dataset = hdf5::Dataset(H5Dopen2(file_id, ds.c_str(), H5P_DEFAULT), file, "H5Dopen2", ds);
  check_matlab_dataset(column.dataset.get(), file, ds, role_text);
  hdf5::Datatype type(H5Dget_type(column.dataset.get()), file, "H5Dget_type", ds);
  const H5T_class_t type_class = H5Tget_class(type.get());
  if (type_class != H5T_FLOAT && type_class != H5T_INTEGER)
    throw DataError(fmt::format("{}: error: {} ({}) holds {}, not numbers; rheo reads a dataset of floating-point or integer numbers", shown,
                                lang::printable(ds), role_text,
                                type_class == H5T_STRING     ? "strings"
                                : type_class == H5T_COMPOUND ? "records (a compound type)"
                                : type_class == H5T_ARRAY    ? "arrays"
                                                             : "values of another kind"));
  column.space = hdf5::Dataspace(H5Dget_space(column.dataset.get()), file, "H5Dget_space", ds);
  const int rank = H5Sget_simple_extent_ndims(column.space.get());
  hdf5::check(rank, file, "H5Sget_simple_extent_ndims", ds);
  hsize_t dims[2] = {0, 0};
  if (rank == 1 || rank == 2) hdf5::check(H5Sget_simple_extent_dims(column.space.get(), dims, nullptr), file, "H5Sget_simple_extent_dims", ds);
  if (rank == 1) column.length = dims[0];
  else if (rank == 2 && dims[1] == 1) column.length = dims[0];
  else if (rank == 2 && dims[0] == 1) column.length = dims[1], column.axis = 1;
  else
    throw DataError(fmt::format("{}: error: {} ({}) has rank {}{}; rheo reads a vector: rank 1, or an N x 1 or 1 x N matrix", shown,
                                lang::printable(ds), role_text, rank, rank == 2 ? fmt::format(" ({} x {})", dims[0], dims[1]) : ""));

  std::string unit_origin = "on the line";
  if (!unit) unit = hdf5::string_attribute(column.dataset.get(), "units", file, ds, kUnitAdvice), unit_origin = "its 'units' attribute";
  const std::string example = role_unit_example(role);
  if ((!unit || unit->empty()) && matlab_class(column.dataset.get(), file, ds))
    throw DataError(
        fmt::format("{}: error: {} ({}) has no unit: MATLAB saves none, and it has no 'units' attribute; write each variable's "
                    "unit after it: {}",
                    shown, lang::printable(ds), role_text, naming));
  if (!unit || unit->empty())
    throw DataError(
        fmt::format("{}: error: {} ({}) has no unit: no 'units' attribute; give it one (a string, e.g. \"{}\"), or write the unit "
                    "after the dataset: columns = \"{} = {} [{}]\"",
                    shown, lang::printable(ds), role_text, example, role_text, lang::printable(ds), example));
  const auto parsed = table_unit(*unit);
  if (!parsed)
    throw DataError(fmt::format("{}: error: {} ({}) has unit '{}' ({}), which rheo does not know; use units such as s, ms, mm, um, m, N, kN", shown,
                                lang::printable(ds), role_text, lang::printable(*unit), unit_origin));
  if (parsed->dimension != role_dimension(role))
    throw DataError(fmt::format("{}: error: {} ({}) has unit '{}' ({}), {}; {} needs a unit of {}, e.g. \"{}\"", shown, lang::printable(ds),
                                role_text, lang::printable(*unit), unit_origin,
                                parsed->dimension.dimensionless() ? std::string("a plain number") : "a " + lang::describe(parsed->dimension),
                                role_text, role_unit_kind(role), example));
  column.scale = parsed->scale;
  return column;
}

}  // namespace

std::vector<Hdf5Column> hdf5_columns(hid_t file_id, const std::string& file, const std::vector<Role>& roles, const ColumnReading& reading) {
  // The root's datasets as a table's header, for the roles the reading does not name; read only
  // where one is not named, so that a file whose every role is named is not held to the root's
  // other datasets (their units attributes).
  Table root;
  root.path = file;
  std::vector<std::string> root_members;
  bool root_read = false;
  const auto read_root = [&] {
    if (std::exchange(root_read, true)) return;
    root_members = members(file_id, file, "/");
    for (const auto& name : root_members) {
      if (object_type(file_id, "/" + name, file) != H5I_DATASET) continue;
      hdf5::Dataset dataset(H5Dopen2(file_id, ("/" + name).c_str(), H5P_DEFAULT), file, "H5Dopen2", "/" + name);
      const std::string unit = hdf5::string_attribute(dataset.get(), "units", file, "/" + name, kUnitAdvice).value_or("");
      root.names.push_back(name), root.units.push_back(unit), root.parsed.push_back(unit.empty() ? std::nullopt : table_unit(unit));
      root.unit_columns.push_back(1), root.problems.emplace_back(), root.columns.emplace_back();
    }
  };
  // Each role's path and the unit written after it, then the datasets opened.
  struct Found {
    Role role;
    std::string path;
    std::optional<std::string> unit;
  };
  std::vector<Found> found;
  for (const Role role : roles) {
    const std::string role_text(role_name(role));
    std::string named;
    for (const auto& [r, name] : reading.columns)
      if (r == role) named = name;
    if (!named.empty()) {
      auto [path, unit] = path_and_unit(named);
      path = absolute(matlab_field_path(file, path));
      check_named_path(file_id, file, path, role_text);
      found.push_back({role, path, unit});
      continue;
    }
    read_root();
    const int c = find_role(root, role, reading);
    if (c < 0)
      throw DataError(
          fmt::format("{}: error: no {} dataset: the root group has none named as usual ({}); name the one that holds it: "
                      "columns = \"{} = /group/dataset\" (the root group holds {})",
                      lang::printable(file), role_text, role_usual_names(role), role_text, listed(root_members)));
    found.push_back({role, "/" + root.names[static_cast<std::size_t>(c)], std::nullopt});
  }
  std::string naming;
  for (const auto& f : found)
    naming += fmt::format("{}{} = {} [{}]", naming.empty() ? "columns = \"" : ", ", role_name(f.role), lang::printable(f.path.substr(1)),
                          f.unit.value_or(role_unit_example(f.role)));
  naming += "\"";
  std::vector<Hdf5Column> columns;
  for (const auto& f : found) columns.push_back(open_column(file_id, file, f.role, f.path, f.unit, naming));
  return columns;
}

}  // namespace rheo::runtime
