// Bounded whole-file reads (lang/file_text.hpp): a file of exactly the bound is read whole, one
// byte more is refused with its size named, and missing files and directories say why.
#include "lang/file_text.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace file_text_test {

using rheo::lang::read_file_text;
namespace fs = std::filesystem;

TEST_CASE("read_file_text reads up to its bound and refuses more, naming the bound and the advice") {
  const fs::path dir = fs::temp_directory_path() / ("rheo-file-text-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::size_t bound = std::size_t{1} << 20;  // 1 MiB; more than one 64 KiB chunk
  const std::string exact(bound, 'x');
  std::ofstream(dir / "exact.txt", std::ios::binary) << exact;
  std::ofstream(dir / "over.txt", std::ios::binary) << exact << 'y';

  const auto whole = read_file_text((dir / "exact.txt").string(), bound);
  CHECK(whole.failure.empty());
  CHECK(whole.text == exact);

  const auto over = read_file_text((dir / "over.txt").string(), bound);
  CHECK(over.failure == "it is larger than 1 MiB, the most rheo reads");
  CHECK(over.text.empty());
  CHECK(std::string(over.advice()) == "is it the right file?");

  const auto missing = read_file_text((dir / "missing.txt").string(), bound);
  CHECK(missing.failure == "No such file or directory");
  CHECK(std::string(missing.advice()) == "check the path");
  CHECK(read_file_text(dir.string(), bound).failure == "it is a directory");

  // A regular file is held in one allocation of its size (growing by doubling held up to twice
  // it: 2 MiB for this 1.1 MiB file), and one past the bound is refused from its size: a sparse
  // file of 1 TiB, which reading would take minutes, at once.
  const std::string odd(bound + bound / 10, 'z');
  std::ofstream(dir / "odd.txt", std::ios::binary) << odd;
  const auto held = read_file_text((dir / "odd.txt").string(), 2 * bound);
  CHECK(held.text == odd);
  CHECK(held.text.capacity() < odd.size() + 4096);
  { std::ofstream(dir / "sparse.txt", std::ios::binary) << 'x'; }
  fs::resize_file(dir / "sparse.txt", std::uintmax_t{1} << 40);
  CHECK(read_file_text((dir / "sparse.txt").string(), bound).failure == "it is larger than 1 MiB, the most rheo reads");

  const auto endless = read_file_text("/dev/zero", bound);
  CHECK(endless.failure == "it is larger than 1 MiB, the most rheo reads");
  fs::remove_all(dir);
}

}  // namespace file_text_test
