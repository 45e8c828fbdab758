#include "runtime/io/hdf5_writer.hpp"

#include "lang/text_encoding.hpp"
#include "runtime/io/matlab_file.hpp"
#include "runtime/io/output_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <ctime>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace rheo::runtime {
namespace {

namespace fs = std::filesystem;

// OBJECT's attribute NAME, a UTF-8 string of variable length (as h5py writes a str).
void write_string_attribute(hid_t object, const char* name, const std::string& value, const std::string& file, const std::string& what) {
  const std::string where = fmt::format("the '{}' attribute of {}", name, what);
  hdf5::Datatype type(H5Tcopy(H5T_C_S1), file, "H5Tcopy", where);
  hdf5::check(H5Tset_size(type.get(), H5T_VARIABLE), file, "H5Tset_size", where);
  hdf5::check(H5Tset_cset(type.get(), H5T_CSET_UTF8), file, "H5Tset_cset", where);
  hdf5::Dataspace scalar(H5Screate(H5S_SCALAR), file, "H5Screate", where);
  hdf5::Attribute attribute(H5Acreate2(object, name, type.get(), scalar.get(), H5P_DEFAULT, H5P_DEFAULT), file, "H5Acreate2", where);
  const char* text = value.c_str();
  hdf5::check(H5Awrite(attribute.get(), type.get(), &text), file, "H5Awrite", where);
}

// OBJECT's attribute MATLAB_class, a fixed-length ASCII string as MATLAB writes it: "double" for
// a numeric array, "struct" for a group of fields.
void write_matlab_class(hid_t object, const char* matlab_class, const std::string& file, const std::string& what) {
  const std::string where = fmt::format("the 'MATLAB_class' attribute of {}", what);
  hdf5::Datatype type(H5Tcopy(H5T_C_S1), file, "H5Tcopy", where);
  hdf5::check(H5Tset_size(type.get(), std::char_traits<char>::length(matlab_class)), file, "H5Tset_size", where);
  hdf5::Dataspace scalar(H5Screate(H5S_SCALAR), file, "H5Screate", where);
  hdf5::Attribute attribute(H5Acreate2(object, "MATLAB_class", type.get(), scalar.get(), H5P_DEFAULT, H5P_DEFAULT), file, "H5Acreate2", where);
  hdf5::check(H5Awrite(attribute.get(), type.get(), matlab_class), file, "H5Awrite", where);
}

// Whether NAME can be a MATLAB struct field: a letter, then letters, digits and '_', at most 63.
bool matlab_field_name(const std::string& name) {
  return !name.empty() && name.size() <= 63 && std::isalpha(static_cast<unsigned char>(name.front())) &&
         std::all_of(name.begin(), name.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

// The 128 bytes MATLAB reads at the start of a v7.3 MAT-file's user block: 116 bytes of text,
// 8 bytes of subsystem offset (none), the version 0x0200 and the endian indicator "IM" (the
// version's bytes as a little-endian machine writes them).
std::array<char, 128> matlab_header() {
  std::array<char, 128> header{};
  std::fill(header.begin(), header.begin() + 116, ' ');
  const std::time_t now = std::time(nullptr);
  char created[32] = "";
  std::tm utc{};
  if (gmtime_r(&now, &utc)) std::strftime(created, sizeof created, "%a %b %d %H:%M:%S %Y", &utc);
  const std::string text = fmt::format("MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: {} HDF5 schema 1.00 .", created);
  std::copy_n(text.begin(), std::min<std::size_t>(text.size(), 116), header.begin());
  header[124] = 0x00, header[125] = 0x02, header[126] = 'I', header[127] = 'M';
  return header;
}

}  // namespace

Hdf5HistoryWriter::Hdf5HistoryWriter(const std::string& path) : path_(path), matlab_(is_matlab_name(path)) {
  hdf5::library();
  check_output_destination(path);
  if (path.empty() || path == "-") throw DataError("-: error: HDF5 output needs a file; name one with -o FILE.h5");
  target_ = link_target(path);
  std::error_code error;
  const auto status = fs::status(target_, error);
  if (fs::exists(status) && !fs::is_regular_file(status))
    throw DataError(
        fmt::format("{}: error: HDF5 output needs a regular file, not a device or pipe; name a file, e.g. result.h5", lang::printable(path)));
}

Hdf5HistoryWriter::~Hdf5HistoryWriter() {
  if (!committed_) discard();
}

void Hdf5HistoryWriter::discard() {
  series_.clear();
  file_.close();
  if (!temporary_.empty()) {
    std::error_code error;
    fs::remove(temporary_, error);
    temporary_.clear();
  }
  fill_ = 0, written_ = 0;
}

void Hdf5HistoryWriter::create_series(const std::string& path, const char* unit) {
  const std::string& file = path_;
  // HDF5 names dimensions slowest first, MATLAB fastest first: a 1 x N dataset is MATLAB's N x 1 column.
  const int rank = matlab_ ? 2 : 1;
  const std::array<hsize_t, 2> none = matlab_ ? std::array<hsize_t, 2>{1, 0} : std::array<hsize_t, 2>{0, 0};
  const std::array<hsize_t, 2> unlimited = matlab_ ? std::array<hsize_t, 2>{1, H5S_UNLIMITED} : std::array<hsize_t, 2>{H5S_UNLIMITED, 0};
  const std::array<hsize_t, 2> chunk = matlab_ ? std::array<hsize_t, 2>{1, kChunkSamples} : std::array<hsize_t, 2>{kChunkSamples, 0};
  hdf5::Dataspace space(H5Screate_simple(rank, none.data(), unlimited.data()), file, "H5Screate_simple", path);
  hdf5::PropertyList links(H5Pcreate(H5P_LINK_CREATE), file, "H5Pcreate", path);
  hdf5::check(H5Pset_create_intermediate_group(links.get(), 1), file, "H5Pset_create_intermediate_group", path);
  hdf5::PropertyList layout(H5Pcreate(H5P_DATASET_CREATE), file, "H5Pcreate", path);
  hdf5::check(H5Pset_chunk(layout.get(), rank, chunk.data()), file, "H5Pset_chunk", path);
  Series series;
  series.path = path;
  series.dataset = hdf5::Dataset(H5Dcreate2(file_.get(), path.c_str(), H5T_IEEE_F64LE, space.get(), links.get(), layout.get(), H5P_DEFAULT), file,
                                 "H5Dcreate2", path);
  write_string_attribute(series.dataset.get(), "units", unit, file, path);
  if (matlab_) write_matlab_class(series.dataset.get(), "double", file, path);
  series.buffer.resize(kChunkSamples);
  series_.push_back(std::move(series));
}

// MATLAB: each group of /elements/... is a struct (elements.maxwell1.force), its FIELDS listed in
// its MATLAB_fields attribute (a vlen array of vlen char sequences), as MATLAB writes them.
void Hdf5HistoryWriter::create_struct(const std::string& path, const std::vector<std::string>& fields) {
  for (const std::string& name : fields)
    if (!matlab_field_name(name))
      throw DataError(
          fmt::format("{}: error: the element name '{}' cannot be a MATLAB struct field (a letter, then letters, digits and '_', "
                      "at most 63); rename the element, or write the element outputs as HDF5 (-o result.h5) or CSV",
                      lang::printable(path_), lang::printable(name)));
  hdf5::Group group(H5Gcreate2(file_.get(), path.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), path_, "H5Gcreate2", path);
  write_matlab_class(group.get(), "struct", path_, path);
  const std::string where = fmt::format("the 'MATLAB_fields' attribute of {}", path);
  hdf5::Datatype letter(H5Tcopy(H5T_C_S1), path_, "H5Tcopy", where);
  hdf5::check(H5Tset_size(letter.get(), 1), path_, "H5Tset_size", where);
  hdf5::Datatype sequence(H5Tvlen_create(letter.get()), path_, "H5Tvlen_create", where);
  const hsize_t count = fields.size();
  hdf5::Dataspace space(H5Screate_simple(1, &count, nullptr), path_, "H5Screate_simple", where);
  std::vector<hvl_t> names(fields.size());
  for (std::size_t i = 0; i < fields.size(); ++i) names[i] = hvl_t{fields[i].size(), const_cast<char*>(fields[i].data())};
  hdf5::Attribute attribute(H5Acreate2(group.get(), "MATLAB_fields", sequence.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), path_, "H5Acreate2",
                            where);
  hdf5::check(H5Awrite(attribute.get(), sequence.get(), names.data()), path_, "H5Awrite", where);
}

void Hdf5HistoryWriter::begin(const ResultHeader& header, const std::vector<std::string>& element_paths) {
  discard();
  temporary_ = temporary_beside(target_);
  const std::string& file = path_;
  hdf5::PropertyList creation(H5Pcreate(H5P_FILE_CREATE), file, "H5Pcreate", "the file");
  if (matlab_) hdf5::check(H5Pset_userblock(creation.get(), kMatlabUserBlock), file, "H5Pset_userblock", "the file");
  file_ = hdf5::File(H5Fcreate(temporary_.c_str(), H5F_ACC_EXCL, creation.get(), H5P_DEFAULT), file, "H5Fcreate",
                     fmt::format("the temporary file {} (is the directory writable?)", temporary_.filename().string()));
  write_string_attribute(file_.get(), "model", header.model, file, "/");
  write_string_attribute(file_.get(), "source", header.source, file, "/");
  write_string_attribute(file_.get(), "protocol", header.protocol, file, "/");
  write_string_attribute(file_.get(), "generator", "rheo", file, "/");
  create_series("/time", "s");
  create_series("/displacement", "mm");
  create_series("/force", "N");
  if (matlab_) {
    // Every struct and its fields, parents first: an element path a.b is elements.a.b.
    std::vector<std::pair<std::string, std::vector<std::string>>> structs;
    const auto fields_of = [&](const std::string& group) -> std::vector<std::string>& {
      for (auto& [path, fields] : structs)
        if (path == group) return fields;
      return structs.emplace_back(group, std::vector<std::string>{}).second;
    };
    fields_of("/elements");
    for (const auto& element : element_paths) {
      std::string group = "/elements";
      for (std::size_t from = 0;;) {
        const std::size_t dot = element.find('.', from);
        const std::string name = element.substr(from, dot == std::string::npos ? std::string::npos : dot - from);
        auto& fields = fields_of(group);
        if (std::find(fields.begin(), fields.end(), name) == fields.end()) fields.push_back(name);
        group += "/" + name;
        if (dot == std::string::npos) break;
        from = dot + 1;
      }
      fields_of(group) = {"force", "elongation"};
    }
    if (!element_paths.empty())
      for (const auto& [path, fields] : structs) create_struct(path, fields);
  }
  for (const auto& element : element_paths) {
    std::string group = "/elements/" + element;
    if (matlab_) std::replace(group.begin(), group.end(), '.', '/');
    create_series(group + "/force", "N");
    create_series(group + "/elongation", "mm");
  }
}

void Hdf5HistoryWriter::flush() {
  if (fill_ == 0) return;
  // The sample axis is the last (MATLAB's 1 x N) or the only one.
  const std::array<hsize_t, 2> start = matlab_ ? std::array<hsize_t, 2>{0, written_} : std::array<hsize_t, 2>{written_, 0};
  const std::array<hsize_t, 2> count = matlab_ ? std::array<hsize_t, 2>{1, fill_} : std::array<hsize_t, 2>{fill_, 0};
  const std::array<hsize_t, 2> size = matlab_ ? std::array<hsize_t, 2>{1, written_ + fill_} : std::array<hsize_t, 2>{written_ + fill_, 0};
  const int rank = matlab_ ? 2 : 1;
  for (auto& series : series_) {
    const std::string& what = series.path;
    hdf5::check(H5Dset_extent(series.dataset.get(), size.data()), path_, "H5Dset_extent", what);
    hdf5::Dataspace space(H5Dget_space(series.dataset.get()), path_, "H5Dget_space", what);
    hdf5::check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr), path_, "H5Sselect_hyperslab", what);
    hdf5::Dataspace memory(H5Screate_simple(rank, count.data(), nullptr), path_, "H5Screate_simple", what);
    hdf5::check(H5Dwrite(series.dataset.get(), H5T_NATIVE_DOUBLE, memory.get(), space.get(), H5P_DEFAULT, series.buffer.data()), path_, "H5Dwrite",
                what + " (disk full?)");
  }
  written_ += fill_;
  fill_ = 0;
}

void Hdf5HistoryWriter::write(const History& piece) {
  if (!file_) throw std::logic_error("Hdf5HistoryWriter::write before begin");
  const std::size_t elements = piece.element_force.size();
  if (series_.size() != 3 + 2 * elements) throw std::logic_error("Hdf5HistoryWriter::write: a piece with other elements than begin() named");
  const std::size_t n = piece.time.size();
  for (std::size_t k = 0; k < n;) {
    const std::size_t take = std::min(n - k, kChunkSamples - fill_);
    const auto from = static_cast<std::ptrdiff_t>(k), to = static_cast<std::ptrdiff_t>(k + take);
    const auto at = static_cast<std::ptrdiff_t>(fill_);
    std::copy(piece.time.begin() + from, piece.time.begin() + to, series_[0].buffer.begin() + at);
    std::copy(piece.displacement.begin() + from, piece.displacement.begin() + to, series_[1].buffer.begin() + at);
    std::copy(piece.force.begin() + from, piece.force.begin() + to, series_[2].buffer.begin() + at);
    for (std::size_t e = 0; e < elements; ++e) {
      std::copy(piece.element_force[e].begin() + from, piece.element_force[e].begin() + to, series_[3 + 2 * e].buffer.begin() + at);
      std::copy(piece.element_elongation[e].begin() + from, piece.element_elongation[e].begin() + to, series_[4 + 2 * e].buffer.begin() + at);
    }
    fill_ += take, k += take;
    if (fill_ == kChunkSamples) flush();
  }
}

void Hdf5HistoryWriter::restart() { discard(); }

void Hdf5HistoryWriter::commit() {
  if (committed_) throw std::logic_error("Hdf5HistoryWriter committed twice");
  if (!file_) throw std::logic_error("Hdf5HistoryWriter::commit before begin");
  flush();
  for (auto& series : series_) hdf5::check(series.dataset.close(), path_, "H5Dclose", series.path);
  series_.clear();
  hdf5::check(file_.close(), path_, "H5Fclose", "the file (disk full?); nothing was written");
  std::error_code error;
  if (matlab_) {
    const std::array<char, 128> header = matlab_header();
    std::fstream out(temporary_, std::ios::in | std::ios::out | std::ios::binary);
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    out.close();
    if (!out) {
      fs::remove(temporary_, error);
      throw DataError(fmt::format("{}: error: cannot write the MAT-file's header (disk full?); nothing was written", lang::printable(path_)));
    }
  }
  fs::rename(temporary_, target_, error);
  if (error) {
    fs::remove(temporary_, error);
    throw DataError(fmt::format("{}: error: cannot replace the output file ({})", lang::printable(path_), error.message()));
  }
  temporary_.clear();
  committed_ = true;
}

}  // namespace rheo::runtime
