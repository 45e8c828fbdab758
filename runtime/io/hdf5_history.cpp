#include "runtime/io/hdf5_history.hpp"

#include "lang/limits.hpp"
#include "lang/text_encoding.hpp"
#include "runtime/io/drive_faults.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>

namespace rheo::runtime {
namespace {

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return text;
}

// "/rig/t [ms]": the path and the unit written after it (nullopt: none written).
std::pair<std::string, std::optional<std::string>> path_and_unit(const std::string& named) {
  const auto open = named.rfind('[');
  if (named.empty() || named.back() != ']' || open == std::string::npos) return {named, std::nullopt};
  std::string path = named.substr(0, open);
  while (!path.empty() && (path.back() == ' ' || path.back() == '\t')) path.pop_back();
  return {path, named.substr(open + 1, named.size() - open - 2)};
}

std::string usual_names(Role role) {
  switch (role) {
    case Role::time: return "time, t";
    case Role::force: return "force, load";
    default: return "displacement, position, disp";
  }
}

std::string absolute(const std::string& path) { return path.starts_with('/') ? path : "/" + path; }

herr_t collect_name(hid_t, const char* name, const H5L_info_t*, void* out) {
  static_cast<std::vector<std::string>*>(out)->emplace_back(name);
  return 0;
}

// The names GROUP holds, for messages.
std::vector<std::string> members(hid_t group, const std::string& file, const std::string& group_path) {
  std::vector<std::string> names;
  hdf5::check(H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_name, &names), file, "H5Literate", group_path);
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

// The string held by DATASET's attribute NAME; nullopt when it has none. DataError when it is
// not one string.
std::optional<std::string> string_attribute(hid_t dataset, const char* name, const std::string& file, const std::string& path) {
  const htri_t has = H5Aexists(dataset, name);
  hdf5::check(has, file, "H5Aexists", path);
  if (has == 0) return std::nullopt;
  const std::string what = fmt::format("the '{}' attribute of {}", name, path);
  hdf5::Attribute attribute(H5Aopen(dataset, name, H5P_DEFAULT), file, "H5Aopen", what);
  hdf5::Datatype type(H5Aget_type(attribute.get()), file, "H5Aget_type", what);
  hdf5::Dataspace space(H5Aget_space(attribute.get()), file, "H5Aget_space", what);
  const hssize_t points = H5Sget_simple_extent_npoints(space.get());
  if (H5Tget_class(type.get()) != H5T_STRING || points != 1)
    throw DataError(fmt::format("{}: error: {} is not a string; write the unit as one string, e.g. \"mm\"", lang::printable(file), what));
  hdf5::Datatype memory(H5Tcopy(H5T_C_S1), file, "H5Tcopy", what);
  hdf5::check(H5Tset_cset(memory.get(), H5Tget_cset(type.get())), file, "H5Tset_cset", what);
  const htri_t variable = H5Tis_variable_str(type.get());
  hdf5::check(variable, file, "H5Tis_variable_str", what);
  std::string text;
  if (variable > 0) {
    hdf5::check(H5Tset_size(memory.get(), H5T_VARIABLE), file, "H5Tset_size", what);
    char* value = nullptr;
    hdf5::check(H5Aread(attribute.get(), memory.get(), &value), file, "H5Aread", what);
    if (value) text = value;
    H5free_memory(value);
  } else {
    const std::size_t size = H5Tget_size(type.get());
    std::vector<char> value(size + 1, '\0');  // a null-padded string of SIZE bytes keeps them all
    hdf5::check(H5Tset_size(memory.get(), size + 1), file, "H5Tset_size", what);
    hdf5::check(H5Aread(attribute.get(), memory.get(), value.data()), file, "H5Aread", what);
    text = value.data();
  }
  while (!text.empty() && (text.back() == ' ' || text.back() == '\0')) text.pop_back();
  return text;
}

}  // namespace

bool is_hdf5_name(const std::string& path) {
  const std::string name = lower(path);
  return name.ends_with(".h5") || name.ends_with(".hdf5");
}

struct Hdf5HistoryReader::Column {
  Role role;
  std::string path;  // absolute
  hdf5::Dataset dataset;
  hdf5::Dataspace space;
  int axis = 0;  // the dimension the samples run along
  int rank = 1;
  hsize_t length = 0;
  double scale = 1.0;  // internal unit per unit of the dataset
};

Hdf5HistoryReader::Hdf5HistoryReader(std::string path, const lang::SourceLocation* named_at, const ColumnReading& reading, bool force,
                                     bool from_rest, std::size_t piece_samples)
    : path_(std::move(path)), from_rest_(from_rest), piece_samples_(std::max<std::size_t>(piece_samples, 1)) {
  hdf5::library();
  const std::string& file = path_;
  const std::string shown = lang::printable(file);
  {
    std::error_code error;
    if (std::filesystem::is_directory(file, error)) throw DataError(unreadable_table(file, named_at, "it is a directory", "name a file"));
    std::FILE* probe = std::fopen(file.c_str(), "rb");
    if (!probe) throw DataError(unreadable_table(file, named_at, std::strerror(errno), "check the name and that the file is readable"));
    std::fclose(probe);
  }
  const htri_t is_hdf5 = H5Fis_hdf5(file.c_str());
  if (is_hdf5 <= 0) {
    hdf5::last_error();
    throw DataError(
        fmt::format("{}: error: this is not an HDF5 file (rheo reads a file named .h5 or .hdf5 as HDF5); give the HDF5 file, "
                    "or name a CSV table .csv",
                    shown));
  }
  file_ = hdf5::File(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), file, "H5Fopen", "the file");
  hsize_t bytes = 0;
  hdf5::check(H5Fget_filesize(file_.get(), &bytes), file, "H5Fget_filesize", "the file");
  file_bytes_ = bytes;

  // The root's datasets as a table's header, for the roles the reading does not name.
  Table root;
  root.path = file;
  std::vector<std::string> root_members = members(file_.get(), file, "/");
  for (const auto& name : root_members) {
    if (object_type(file_.get(), "/" + name, file) != H5I_DATASET) continue;
    hdf5::Dataset dataset(H5Dopen2(file_.get(), ("/" + name).c_str(), H5P_DEFAULT), file, "H5Dopen2", "/" + name);
    const std::string unit = string_attribute(dataset.get(), "units", file, "/" + name).value_or("");
    root.names.push_back(name), root.units.push_back(unit), root.parsed.push_back(unit.empty() ? std::nullopt : table_unit(unit));
    root.unit_columns.push_back(1), root.problems.emplace_back(), root.columns.emplace_back();
  }

  std::vector<Role> roles{Role::time, Role::displacement};
  if (force) roles.push_back(Role::force);
  for (const Role role : roles) {
    const std::string role_text(role_name(role));
    std::string named;
    for (const auto& [r, name] : reading.columns)
      if (r == role) named = name;
    std::optional<std::string> unit;
    std::string dataset_path;
    if (!named.empty()) {
      auto [p, u] = path_and_unit(named);
      dataset_path = absolute(p), unit = u;
      // Each group on the way, then the dataset: the first that is missing is named.
      std::string at;
      std::size_t from = 1;
      while (true) {
        const auto slash = dataset_path.find('/', from);
        const std::string next = dataset_path.substr(0, slash);
        const std::string parent = at.empty() ? "/" : at;
        const htri_t exists = H5Lexists(file_.get(), next.c_str(), H5P_DEFAULT);
        hdf5::check(exists, file, "H5Lexists", next);
        if (exists == 0) {
          hdf5::Group group(H5Gopen2(file_.get(), parent.c_str(), H5P_DEFAULT), file, "H5Gopen2", parent);
          throw DataError(fmt::format("{}: error: no dataset {} for {}: there is no {}; {} holds {}", shown, lang::printable(dataset_path),
                                      role_text, lang::printable(next), parent == "/" ? "the root group" : lang::printable(parent),
                                      listed(members(group.get(), file, parent))));
        }
        const H5I_type_t type = object_type(file_.get(), next, file);
        if (slash == std::string::npos) {
          if (type == H5I_GROUP) {
            hdf5::Group group(H5Gopen2(file_.get(), next.c_str(), H5P_DEFAULT), file, "H5Gopen2", next);
            throw DataError(fmt::format("{}: error: {} ({}) is a group, not a dataset; name a dataset in it: it holds {}", shown,
                                        lang::printable(next), role_text, listed(members(group.get(), file, next))));
          }
          if (type != H5I_DATASET)
            throw DataError(fmt::format("{}: error: {} ({}) is not a dataset; name the dataset that holds the {}", shown, lang::printable(next),
                                        role_text, role_text));
          break;
        }
        if (type != H5I_GROUP)
          throw DataError(fmt::format("{}: error: no dataset {} for {}: {} is not a group", shown, lang::printable(dataset_path), role_text,
                                      lang::printable(next)));
        at = next;
        from = slash + 1;
      }
    } else {
      const int c = find_role(root, role, reading);
      if (c < 0)
        throw DataError(
            fmt::format("{}: error: no {} dataset: the root group has none named as usual ({}); name the one that holds it: "
                        "columns = \"{} = /group/dataset\" (the root group holds {})",
                        shown, role_text, usual_names(role), role_text, listed(root_members)));
      dataset_path = "/" + root.names[static_cast<std::size_t>(c)];
    }

    auto column = std::make_unique<Column>();
    column->role = role;
    column->path = dataset_path;
    const std::string& ds = column->path;
    column->dataset = hdf5::Dataset(H5Dopen2(file_.get(), ds.c_str(), H5P_DEFAULT), file, "H5Dopen2", ds);
    hdf5::Datatype type(H5Dget_type(column->dataset.get()), file, "H5Dget_type", ds);
    const H5T_class_t type_class = H5Tget_class(type.get());
    if (type_class != H5T_FLOAT && type_class != H5T_INTEGER)
      throw DataError(fmt::format("{}: error: {} ({}) holds {}, not numbers; rheo reads a dataset of floating-point or integer numbers", shown,
                                  lang::printable(ds), role_text,
                                  type_class == H5T_STRING     ? "strings"
                                  : type_class == H5T_COMPOUND ? "records (a compound type)"
                                  : type_class == H5T_ARRAY    ? "arrays"
                                                               : "values of another kind"));
    column->space = hdf5::Dataspace(H5Dget_space(column->dataset.get()), file, "H5Dget_space", ds);
    const int rank = H5Sget_simple_extent_ndims(column->space.get());
    hdf5::check(rank, file, "H5Sget_simple_extent_ndims", ds);
    hsize_t dims[2] = {0, 0};
    if (rank == 1 || rank == 2) hdf5::check(H5Sget_simple_extent_dims(column->space.get(), dims, nullptr), file, "H5Sget_simple_extent_dims", ds);
    column->rank = rank;
    if (rank == 1) column->length = dims[0];
    else if (rank == 2 && dims[1] == 1) column->length = dims[0];
    else if (rank == 2 && dims[0] == 1) column->length = dims[1], column->axis = 1;
    else
      throw DataError(fmt::format("{}: error: {} ({}) has rank {}{}; rheo reads a vector: rank 1, or an N x 1 or 1 x N matrix", shown,
                                  lang::printable(ds), role_text, rank, rank == 2 ? fmt::format(" ({} x {})", dims[0], dims[1]) : ""));

    std::string unit_origin = "on the line";
    if (!unit) unit = string_attribute(column->dataset.get(), "units", file, ds), unit_origin = "its 'units' attribute";
    const std::string example = role_unit_example(role);
    if (!unit || unit->empty())
      throw DataError(
          fmt::format("{}: error: {} ({}) has no unit: no 'units' attribute; give it one (a string, e.g. \"{}\"), or write the unit "
                      "after the dataset: columns = \"{} = {} [{}]\"",
                      shown, lang::printable(ds), role_text, example, role_text, lang::printable(ds), example));
    const auto parsed = table_unit(*unit);
    if (!parsed)
      throw DataError(fmt::format("{}: error: {} ({}) has unit '{}' ({}), which rheo does not know; use units such as s, ms, mm, um, m, N, kN",
                                  shown, lang::printable(ds), role_text, lang::printable(*unit), unit_origin));
    if (parsed->dimension != role_dimension(role))
      throw DataError(fmt::format("{}: error: {} ({}) has unit '{}' ({}), {}; {} needs a unit of {}, e.g. \"{}\"", shown, lang::printable(ds),
                                  role_text, lang::printable(*unit), unit_origin,
                                  parsed->dimension.dimensionless() ? std::string("a plain number") : "a " + lang::describe(parsed->dimension),
                                  role_text, role_unit_kind(role), example));
    column->scale = parsed->scale;
    columns_.push_back(std::move(column));
  }

  const Column& time = *columns_.front();
  for (const auto& column : columns_)
    if (column->length != time.length)
      throw DataError(fmt::format("{}: error: the datasets differ in length: {} has {} samples, {} has {}; a history needs a {} at every time", shown,
                                  lang::printable(time.path), time.length, lang::printable(column->path), column->length, role_name(column->role)));
  if (time.length < 2)
    throw DataError(fmt::format("{}: error: {} has {} sample{}; a history needs at least two", shown, lang::printable(time.path), time.length,
                                time.length == 1 ? "" : "s"));
  samples_ = time.length;
  buffer_.reserve(piece_samples_);
}

Hdf5HistoryReader::~Hdf5HistoryReader() = default;

std::uint64_t Hdf5HistoryReader::bytes_read() const {
  return samples_ == 0 ? 0
                       : static_cast<std::uint64_t>(static_cast<double>(file_bytes_) * static_cast<double>(next_) / static_cast<double>(samples_));
}

void Hdf5HistoryReader::read(Column& column, std::uint64_t start, std::size_t count, std::vector<double>& out) {
  out.resize(count);
  hsize_t offset[2] = {0, 0}, extent[2] = {1, 1};
  offset[column.axis] = start;
  extent[column.axis] = count;
  hdf5::check(H5Sselect_hyperslab(column.space.get(), H5S_SELECT_SET, offset, nullptr, extent, nullptr), path_, "H5Sselect_hyperslab", column.path);
  const hsize_t n = count;
  hdf5::Dataspace memory(H5Screate_simple(1, &n, nullptr), path_, "H5Screate_simple", column.path);
  hdf5::check(H5Dread(column.dataset.get(), H5T_NATIVE_DOUBLE, memory.get(), column.space.get(), H5P_DEFAULT, out.data()), path_, "H5Dread",
              column.path);
  if (column.scale != 1.0)
    for (double& v : out) v *= column.scale;
}

void Hdf5HistoryReader::value_fault(const Column& column, std::uint64_t index, const std::string& what, const std::string& advice) {
  fault_ = fmt::format("{}: error: {}[{}] ({}) {}; {}", lang::printable(path_), lang::printable(column.path), index, role_name(column.role), what,
                       advice);
  throw DataError(fault_);
}

bool Hdf5HistoryReader::next(DrivePiece& piece, std::vector<double>* force) {
  piece.clear();
  if (force) force->clear();
  if (!fault_.empty()) throw DataError(fault_);  // found before: drain() after a failed next() reports it again
  if (next_ == samples_) {
    if (from_rest_ && !drive_faults::starts_at_rest(u0_, largest_))
      value_fault(*columns_[1], 0, fmt::format("is {:g} mm", u0_),
                  "start = rest needs displacement 0 at the first sample; remove start = rest to start relaxed there, or shift the "
                  "displacement");
    if (columns_.size() > 2 && !force_seen_) {
      fault_ = fmt::format("{}: error: every force in {} is zero; a fit needs a force signal: check the dataset and its unit",
                           lang::printable(path_), lang::printable(columns_[2]->path));
      throw DataError(fault_);
    }
    return false;
  }
  const std::uint64_t first = next_;
  const auto count = static_cast<std::size_t>(std::min<std::uint64_t>(piece_samples_, samples_ - first));
  read(*columns_[0], first, count, piece.time);
  read(*columns_[1], first, count, piece.displacement);
  if (force) read(*columns_[2], first, count, *force);
  else if (columns_.size() > 2) read(*columns_[2], first, count, buffer_);
  const std::vector<double>* forces = force ? force : columns_.size() > 2 ? &buffer_ : nullptr;
  piece.rows.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint64_t i = first + k;
    const double t = piece.time[k], u = piece.displacement[k];
    if (!std::isfinite(t))
      value_fault(*columns_[0], i, fmt::format("is {}", t), "every time must be a finite number: remove the sample or mend the recording");
    if (!std::isfinite(u))
      value_fault(*columns_[1], i, fmt::format("is {}", u), "every displacement must be a finite number: remove the sample or mend the recording");
    if (forces) {
      const double f = (*forces)[k];
      if (!std::isfinite(f))
        value_fault(*columns_[2], i, fmt::format("is {}", f), "every force must be a finite number: remove the sample or mend the recording");
      force_seen_ = force_seen_ || f != 0.0;
    }
    if (i == 0) {
      t0_ = t, u0_ = u;
    } else if (!(t > last_t_)) {
      value_fault(*columns_[0], i, fmt::format("= {:g} s is not after [{}] = {:g} s", t, i - 1, last_t_),
                  "time must increase from sample to sample: remove repeated samples or sort the history by time");
    }
    if (!drive_faults::drivable(u))
      value_fault(*columns_[1], i, fmt::format("= {:g} mm is beyond the {:g} mm a rig can drive", u, lang::max_amplitude),
                  "check the dataset's unit");
    largest_ = std::max(largest_, std::abs(u));
    last_t_ = t;
    piece.time[k] = t - t0_;
    piece.rows[k] = static_cast<int>(std::min<std::uint64_t>(i, static_cast<std::uint64_t>(std::numeric_limits<int>::max())));
  }
  next_ += count;
  return true;
}

void Hdf5HistoryReader::drain() {
  DrivePiece piece;
  while (next(piece)) {}
}

Drive read_hdf5_drive(const std::string& path, const lang::SourceLocation* named_at, const ColumnReading& reading, bool from_rest) {
  Hdf5HistoryReader reader(path, named_at, reading, false, from_rest);
  Drive drive;
  drive.time.reserve(reader.samples()), drive.displacement.reserve(reader.samples());
  DrivePiece piece;
  while (reader.next(piece)) {
    drive.time.insert(drive.time.end(), piece.time.begin(), piece.time.end());
    drive.displacement.insert(drive.displacement.end(), piece.displacement.begin(), piece.displacement.end());
  }
  return drive;
}

HistoryData read_hdf5_history(const std::string& path, const lang::SourceLocation* named_at, const ColumnReading& reading) {
  Hdf5HistoryReader reader(path, named_at, reading, true, false);
  HistoryData h;
  h.path = path;
  const auto n = static_cast<std::size_t>(reader.samples());
  h.drive.time.reserve(n), h.drive.displacement.reserve(n), h.force.reserve(n), h.rows.reserve(n);
  DrivePiece piece;
  std::vector<double> force;
  while (reader.next(piece, &force)) {
    h.drive.time.insert(h.drive.time.end(), piece.time.begin(), piece.time.end());
    h.drive.displacement.insert(h.drive.displacement.end(), piece.displacement.begin(), piece.displacement.end());
    h.force.insert(h.force.end(), force.begin(), force.end());
    h.rows.insert(h.rows.end(), piece.rows.begin(), piece.rows.end());
  }
  h.force_scale = 0.0;
  for (double v : h.force) h.force_scale = std::max(h.force_scale, std::abs(v));
  return h;
}

}  // namespace rheo::runtime
