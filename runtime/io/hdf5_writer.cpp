#include "runtime/io/hdf5_writer.hpp"

#include "lang/text_encoding.hpp"
#include "runtime/io/output_file.hpp"

#include <fmt/format.h>

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

}  // namespace

Hdf5HistoryWriter::Hdf5HistoryWriter(const std::string& path) : path_(path) {
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
  const hsize_t none = 0, unlimited = H5S_UNLIMITED, chunk = kChunkSamples;
  hdf5::Dataspace space(H5Screate_simple(1, &none, &unlimited), file, "H5Screate_simple", path);
  hdf5::PropertyList links(H5Pcreate(H5P_LINK_CREATE), file, "H5Pcreate", path);
  hdf5::check(H5Pset_create_intermediate_group(links.get(), 1), file, "H5Pset_create_intermediate_group", path);
  hdf5::PropertyList layout(H5Pcreate(H5P_DATASET_CREATE), file, "H5Pcreate", path);
  hdf5::check(H5Pset_chunk(layout.get(), 1, &chunk), file, "H5Pset_chunk", path);
  Series series;
  series.path = path;
  series.dataset = hdf5::Dataset(H5Dcreate2(file_.get(), path.c_str(), H5T_IEEE_F64LE, space.get(), links.get(), layout.get(), H5P_DEFAULT), file,
                                 "H5Dcreate2", path);
  write_string_attribute(series.dataset.get(), "units", unit, file, path);
  series.buffer.resize(kChunkSamples);
  series_.push_back(std::move(series));
}

void Hdf5HistoryWriter::begin(const ResultHeader& header, const std::vector<std::string>& element_paths) {
  discard();
  temporary_ = temporary_beside(target_);
  const std::string& file = path_;
  file_ = hdf5::File(H5Fcreate(temporary_.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, H5P_DEFAULT), file, "H5Fcreate",
                     fmt::format("the temporary file {} (is the directory writable?)", temporary_.filename().string()));
  write_string_attribute(file_.get(), "model", header.model, file, "/");
  write_string_attribute(file_.get(), "source", header.source, file, "/");
  write_string_attribute(file_.get(), "protocol", header.protocol, file, "/");
  write_string_attribute(file_.get(), "generator", "rheo", file, "/");
  create_series("/time", "s");
  create_series("/displacement", "mm");
  create_series("/force", "N");
  for (const auto& element : element_paths) {
    create_series("/elements/" + element + "/force", "N");
    create_series("/elements/" + element + "/elongation", "mm");
  }
}

void Hdf5HistoryWriter::flush() {
  if (fill_ == 0) return;
  const hsize_t start = written_, count = fill_, size = written_ + fill_;
  for (auto& series : series_) {
    const std::string& what = series.path;
    hdf5::check(H5Dset_extent(series.dataset.get(), &size), path_, "H5Dset_extent", what);
    hdf5::Dataspace space(H5Dget_space(series.dataset.get()), path_, "H5Dget_space", what);
    hdf5::check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, &start, nullptr, &count, nullptr), path_, "H5Sselect_hyperslab", what);
    hdf5::Dataspace memory(H5Screate_simple(1, &count, nullptr), path_, "H5Screate_simple", what);
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
  fs::rename(temporary_, target_, error);
  if (error) {
    fs::remove(temporary_, error);
    throw DataError(fmt::format("{}: error: cannot replace the output file ({})", lang::printable(path_), error.message()));
  }
  temporary_.clear();
  committed_ = true;
}

}  // namespace rheo::runtime
