// libFuzzer target: the input is a displacement history table (runtime/io/history_csv.hpp), read
// from memory into a drive as `history file = ...` reads it from a file; and read again by the
// streamed reader (runtime/io/history_stream.hpp), in blocks of 7 bytes and of 1 MiB, which
// must give the same drive bit for bit or the same error message (else: abort, a crash with
// the input), or leave the file to whole-file reading (NotStreamable).
#include "documented_errors.hpp"
#include "runtime/io/history_csv.hpp"
#include "runtime/io/history_stream.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

struct Reading {
  std::vector<double> time, displacement;
  std::string error;
  bool whole_file = false;  // NotStreamable
};

bool same(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

Reading streamed(const std::string& text, bool from_rest, std::size_t block) {
  Reading r;
  std::FILE* file = std::tmpfile();
  if (!file) std::abort();
  std::fwrite(text.data(), 1, text.size(), file);
  std::rewind(file);
  try {
    rheo::runtime::HistoryStream stream("fuzz.csv", file, from_rest, block);
    rheo::runtime::DrivePiece piece;
    while (stream.next(piece)) {
      r.time.insert(r.time.end(), piece.time.begin(), piece.time.end());
      r.displacement.insert(r.displacement.end(), piece.displacement.begin(), piece.displacement.end());
    }
  } catch (const rheo::runtime::DataError& e) {
    r = Reading{};
    r.error = e.what();
  } catch (const rheo::runtime::NotStreamable&) {
    r = Reading{};
    r.whole_file = true;
  }
  return r;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const bool from_rest = size > 0 && data[0] % 2 == 1;
  Reading whole;
  rheo::fuzz::expect_only_documented_errors([&] {
    try {
      const rheo::runtime::Drive d = rheo::runtime::drive_from_table(rheo::runtime::parse_table("fuzz.csv", text), from_rest);
      whole.time = d.time, whole.displacement = d.displacement;
    } catch (const rheo::runtime::DataError& e) {
      whole.error = e.what();
    }
  });
  for (const std::size_t block : {std::size_t{7}, rheo::runtime::HistoryStream::kBlockBytes}) {
    Reading r;
    rheo::fuzz::expect_only_documented_errors([&] { r = streamed(text, from_rest, block); });
    if (r.whole_file) continue;
    if (r.error != whole.error || !same(r.time, whole.time) || !same(r.displacement, whole.displacement)) {
      std::fprintf(stderr, "rheo fuzz: the streamed reader (block %zu) disagrees with the whole-file one:\n  streamed: %s\n  whole:    %s\n", block,
                   r.error.c_str(), whole.error.c_str());
      std::abort();
    }
  }
  return 0;
}
