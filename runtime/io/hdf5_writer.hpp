// A history written as HDF5 as it is made (core/history_sink.hpp; docs/data-formats.md, "HDF5
// files"): float64 datasets /time [s], /displacement [mm], /force [N] and, with element outputs,
// /elements/PATH/force [N] and /elements/PATH/elongation [mm], each with its unit as a "units"
// string attribute; the root's string attributes "model", "source", "protocol" and "generator"
// say what produced it. Datasets are chunked (kChunkSamples) and extended a whole chunk at a
// time from a buffer of one chunk per dataset: memory does not grow with the history.
//
// A PATH ending in .mat is written as a MATLAB v7.3 MAT-file (docs/data-formats.md, "MATLAB
// files"), which MATLAB's load and matio read: the same HDF5 file behind a 512-byte user block
// with MATLAB's header, each dataset 1 x N (MATLAB's N x 1 column: time, displacement, force)
// with MATLAB_class "double", and /elements and its groups structs (MATLAB_class "struct"; an
// element path a.b becomes elements.a.b.force): an element name MATLAB cannot take as a field
// (one starting with '_') is a DataError at begin().
//
// The file is written to a temporary sibling (output_file.hpp's temporary_beside) and renamed
// over PATH by commit(): a failed run leaves PATH as it was and, destroyed without commit(),
// nothing behind (a killed run leaves the hidden sibling). HDF5 needs a regular file: a device,
// a pipe or standard output is a DataError.
#pragma once

#include "runtime/core/history_sink.hpp"
#include "runtime/io/hdf5_owners.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace rheo::runtime {

class Hdf5HistoryWriter : public HistorySink {
 public:
  static constexpr std::size_t kChunkSamples = 32768;
  static constexpr hsize_t kMatlabUserBlock = 512;

  // Checks that PATH can be written (check_output_destination); creates nothing yet.
  explicit Hdf5HistoryWriter(const std::string& path);
  ~Hdf5HistoryWriter() override;
  Hdf5HistoryWriter(const Hdf5HistoryWriter&) = delete;
  Hdf5HistoryWriter& operator=(const Hdf5HistoryWriter&) = delete;

  void begin(const ResultHeader& header, const std::vector<std::string>& element_paths) override;
  void write(const History& piece) override;
  void restart() override;
  // Writes what is buffered, closes the file and renames it over PATH. Once, after begin().
  void commit();

 private:
  struct Series {
    hdf5::Dataset dataset;
    std::string path;
    std::vector<double> buffer;  // kChunkSamples
  };
  void create_series(const std::string& path, const char* unit);
  void create_struct(const std::string& path, const std::vector<std::string>& fields);
  void flush();
  void discard();  // closes and removes the temporary file

  std::string path_;                 // as given, for messages
  bool matlab_ = false;              // a .mat name: MATLAB's layout
  std::filesystem::path target_;     // the file renamed over (links followed)
  std::filesystem::path temporary_;  // the sibling written
  hdf5::File file_;
  std::vector<Series> series_;  // time, displacement, force, then each element's force and elongation
  std::size_t fill_ = 0;        // samples buffered
  unsigned long long written_ = 0;
  bool committed_ = false;
};

}  // namespace rheo::runtime
