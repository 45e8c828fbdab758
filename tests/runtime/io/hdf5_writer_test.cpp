// The HDF5 history writer, read back with the HDF5 C API (hdf5_support.hpp): every sample of
// every piece, bit for bit, whatever the pieces' sizes against the chunk; units and what
// produced the file as attributes; chunked datasets; nothing in place before commit(), an
// earlier file intact and no temporary left when the writer is dropped or restarted.
#include "runtime/io/hdf5_writer.hpp"

#include "hdf5_support.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/io/hdf5_history.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <matio.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace hdf5_writer_test {

using namespace rheo::runtime;
namespace fs = std::filesystem;
namespace h5 = rheo::test::hdf5;

namespace {

fs::path scratch(const std::string& name) {
  const auto dir = fs::temp_directory_path() / fmt::format("rheo-hdf5-writer-{}-{}", name, ::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Samples [FROM, FROM + N) of a history with two elements; sample k's values are functions of k.
History piece(std::size_t from, std::size_t n) {
  History h;
  h.element_paths = {"rubber", "outer.m1"};
  h.element_force.assign(2, {}), h.element_elongation.assign(2, {});
  for (std::size_t k = from; k < from + n; ++k) {
    const double x = static_cast<double>(k);
    h.time.push_back(x * 1e-4), h.displacement.push_back(std::sin(x * 1e-3)), h.force.push_back(std::cos(x * 1e-3) * 1e3);
    h.element_force[0].push_back(x), h.element_force[1].push_back(-x);
    h.element_elongation[0].push_back(x / 3), h.element_elongation[1].push_back(x / 7);
  }
  return h;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

std::size_t entries(const fs::path& dir) { return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator())); }

}  // namespace

TEST_CASE("an HDF5 history written in pieces reads back bit for bit, with units and its origin as attributes") {
  const auto dir = scratch("pieces");
  const auto file = (dir / "out.h5").string();
  const std::size_t total = 2 * Hdf5HistoryWriter::kChunkSamples + 4321;
  {
    Hdf5HistoryWriter writer(file);
    writer.begin({"d", "model.rheo", "history file=drive.csv"}, {"rubber", "outer.m1"});
    const std::size_t sizes[] = {1, 4096, 7, 40000, Hdf5HistoryWriter::kChunkSamples, 333};  // across, at and inside chunk bounds
    for (std::size_t at = 0, i = 0; at < total; ++i) {
      const std::size_t n = std::min(sizes[i % 6], total - at);
      writer.write(piece(at, n));
      at += n;
    }
    CHECK_FALSE(fs::exists(file));  // not before commit
    writer.commit();
  }
  const History whole = piece(0, total);
  CHECK(same_bits(h5::read_dataset(file, "/time"), whole.time));
  CHECK(same_bits(h5::read_dataset(file, "/displacement"), whole.displacement));
  CHECK(same_bits(h5::read_dataset(file, "/force"), whole.force));
  CHECK(same_bits(h5::read_dataset(file, "/elements/outer.m1/force"), whole.element_force[1]));
  CHECK(same_bits(h5::read_dataset(file, "/elements/rubber/elongation"), whole.element_elongation[0]));
  CHECK(h5::read_string_attribute(file, "/time", "units") == "s");
  CHECK(h5::read_string_attribute(file, "/displacement", "units") == "mm");
  CHECK(h5::read_string_attribute(file, "/elements/rubber/force", "units") == "N");
  CHECK(h5::read_string_attribute(file, "/elements/rubber/elongation", "units") == "mm");
  CHECK(h5::read_string_attribute(file, "/", "model") == "d");
  CHECK(h5::read_string_attribute(file, "/", "protocol") == "history file=drive.csv");
  CHECK(h5::layout_of(file, "/force") == H5D_CHUNKED);
  CHECK(entries(dir) == 1);  // no temporary left
  // rheo's own result is a history rheo reads in its default layout.
  const HistoryData back = read_hdf5_history(file, nullptr, {});
  CHECK(same_bits(back.force, whole.force));
}

TEST_CASE("an HDF5 output is put in place only by commit: dropped or restarted, the earlier file stays and nothing is left") {
  const auto dir = scratch("commit");
  const auto file = (dir / "out.h5").string();
  std::ofstream(file) << "earlier";
  {
    Hdf5HistoryWriter writer(file);
    writer.begin({"d", "m.rheo", "history"}, {});
    History h = piece(0, 100);
    h.element_paths.clear(), h.element_force.clear(), h.element_elongation.clear();
    writer.write(h);
    CHECK(entries(dir) == 2);  // the temporary beside it
  }
  std::ifstream in(file);
  std::string earlier;
  std::getline(in, earlier);
  CHECK(earlier == "earlier");
  CHECK(entries(dir) == 1);
  {
    Hdf5HistoryWriter writer(file);
    writer.begin({"d", "m.rheo", "history"}, {});
    History h = piece(0, 10);
    h.element_paths.clear(), h.element_force.clear(), h.element_elongation.clear();
    writer.write(h);
    writer.restart();
    CHECK(entries(dir) == 1);
    writer.begin({"d", "m.rheo", "history"}, {});
    History g = piece(5, 3);
    g.element_paths.clear(), g.element_force.clear(), g.element_elongation.clear();
    writer.write(g);
    writer.commit();
  }
  CHECK(h5::read_dataset(file, "/time") == piece(5, 3).time);
  CHECK(entries(dir) == 1);
}

TEST_CASE("an HDF5 output in a missing directory, or to a device, is a DataError naming it") {
  CHECK_THROWS_AS(Hdf5HistoryWriter("/nonexistent-rheo-dir/out.h5"), DataError);
  CHECK_THROWS_WITH_AS(Hdf5HistoryWriter("/dev/null"), doctest::Contains("HDF5 output needs a regular file"), DataError);
}

namespace {

// VARIABLE of the MAT-file FILE as matio (an independent implementation of the format) reads
// it: a real double column vector, or empty when it is not one.
std::vector<double> matio_column(const std::string& file, const std::vector<std::string>& variable) {
  mat_t* mat = Mat_Open(file.c_str(), MAT_ACC_RDONLY);
  REQUIRE(mat != nullptr);
  CHECK(Mat_GetVersion(mat) == MAT_FT_MAT73);
  std::vector<double> out;
  if (matvar_t* top = Mat_VarRead(mat, variable.front().c_str())) {
    matvar_t* v = top;
    for (std::size_t i = 1; i < variable.size() && v; ++i) v = Mat_VarGetStructFieldByName(v, variable[i].c_str(), 0);
    if (v && v->class_type == MAT_C_DOUBLE && !v->isComplex && v->rank == 2 && v->dims[1] == 1) {
      const auto* data = static_cast<const double*>(v->data);
      out.assign(data, data + v->dims[0]);
    }
    Mat_VarFree(top);
  }
  Mat_Close(mat);
  return out;
}

}  // namespace

TEST_CASE("a .mat output is a MATLAB v7.3 MAT-file: matio reads its columns and element structs bit for bit, rheo reads it back") {
  const auto dir = scratch("matlab");
  const auto file = (dir / "out.mat").string();
  const std::size_t total = Hdf5HistoryWriter::kChunkSamples + 777;
  {
    Hdf5HistoryWriter writer(file);
    writer.begin({"d", "model.rheo", "history file=drive.csv"}, {"rubber", "outer.m1"});
    writer.write(piece(0, 5000));
    writer.write(piece(5000, total - 5000));
    writer.commit();
  }
  // MATLAB's 128-byte header: its text, version 0x0200 and the endian indicator "IM".
  std::ifstream in(file, std::ios::binary);
  std::string header(128, '\0');
  in.read(header.data(), 128);
  CHECK(header.rfind("MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: ", 0) == 0);
  CHECK(header.substr(124) == std::string("\x00\x02IM", 4));
  const History whole = piece(0, total);
  CHECK(same_bits(matio_column(file, {"time"}), whole.time));
  CHECK(same_bits(matio_column(file, {"displacement"}), whole.displacement));
  CHECK(same_bits(matio_column(file, {"force"}), whole.force));
  CHECK(same_bits(matio_column(file, {"elements", "rubber", "elongation"}), whole.element_elongation[0]));
  CHECK(same_bits(matio_column(file, {"elements", "outer", "m1", "force"}), whole.element_force[1]));
  CHECK(h5::read_string_attribute(file, "/force", "units") == "N");
  // rheo reads its own MAT-file as a history, as it reads MATLAB's.
  const HistoryData back = read_hdf5_history(file, nullptr, {});
  CHECK(same_bits(back.drive.time, whole.time));
  CHECK(same_bits(back.drive.displacement, whole.displacement));
  CHECK(same_bits(back.force, whole.force));
  CHECK(entries(dir) == 1);
}

TEST_CASE("a .mat output refuses an element name MATLAB cannot take as a struct field, and leaves nothing") {
  const auto dir = scratch("matlab-name");
  const auto file = (dir / "out.mat").string();
  {
    Hdf5HistoryWriter writer(file);
    CHECK_THROWS_WITH_AS(writer.begin({"d", "model.rheo", "history"}, {"ok", "outer._hidden"}),
                         doctest::Contains("the element name '_hidden' cannot be a MATLAB struct field"), DataError);
  }
  CHECK(entries(dir) == 0);
  Hdf5HistoryWriter writer(file);  // without element outputs the names do not matter
  writer.begin({"d", "model.rheo", "history"}, {});
  History plain = piece(0, 10);
  plain.element_paths.clear(), plain.element_force.clear(), plain.element_elongation.clear();
  writer.write(plain);
  writer.commit();
  CHECK(matio_column(file, {"force"}).size() == 10);
}

}  // namespace hdf5_writer_test
