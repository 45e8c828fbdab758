#include "lang/file_text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace rheo::lang {

const char* FileText::advice() const { return failure.rfind("it is larger than", 0) == 0 ? "is it the right file?" : "check the path"; }

FileText read_file_text(const std::string& path, std::size_t max_bytes) {
  FileText out;
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    out.failure = "it is a directory";
    return out;
  }
  const auto too_large = [&] { return fmt::format("it is larger than {} MiB, the most rheo reads", max_bytes >> 20); };
  // A regular file says its size: one past the bound is refused before a byte is read, and the
  // text is allocated once (growing by doubling held up to twice the file).
  const bool regular = std::filesystem::is_regular_file(path, error);
  const std::uintmax_t size = regular ? std::filesystem::file_size(path, error) : 0;
  if (regular && !error && size > max_bytes) {
    out.failure = too_large();
    return out;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    out.failure = std::strerror(errno);
    return out;
  }
  if (regular && !error) out.text.reserve(static_cast<std::size_t>(size));
  // Chunks up to one byte past the bound (a file that grows while read, a pipe, a device), so
  // that one of exactly MAX_BYTES is read whole.
  char chunk[1 << 16];
  while (in && out.text.size() <= max_bytes) {
    in.read(chunk, static_cast<std::streamsize>(std::min(sizeof chunk, max_bytes + 1 - out.text.size())));
    out.text.append(chunk, static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) {
    out.failure = std::strerror(errno);
    out.text.clear();
  } else if (out.text.size() > max_bytes) {
    out.failure = too_large();
    out.text.clear();
  }
  return out;
}

}  // namespace rheo::lang
