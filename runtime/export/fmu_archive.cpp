#include "runtime/export/fmu_archive.hpp"

#include <fmt/format.h>
#include <minizip/zip.h>

#include <cstring>
#include <limits>
#include <stdexcept>

namespace rheo::runtime::exporter {
namespace {

// minizip's file functions over a string: the archive grows in memory.
struct Memory {
  std::string bytes;
  std::size_t at = 0;
};

voidpf ZCALLBACK open_memory(voidpf opaque, const void*, int) { return opaque; }
uLong ZCALLBACK read_memory(voidpf, voidpf stream, void* buffer, uLong size) {
  auto& m = *static_cast<Memory*>(stream);
  const std::size_t n = std::min<std::size_t>(size, m.bytes.size() - std::min(m.at, m.bytes.size()));
  std::memcpy(buffer, m.bytes.data() + m.at, n);
  m.at += n;
  return static_cast<uLong>(n);
}
uLong ZCALLBACK write_memory(voidpf, voidpf stream, const void* buffer, uLong size) {
  auto& m = *static_cast<Memory*>(stream);
  if (m.at + size > m.bytes.size()) m.bytes.resize(m.at + size);
  std::memcpy(m.bytes.data() + m.at, buffer, size);
  m.at += size;
  return size;
}
ZPOS64_T ZCALLBACK tell_memory(voidpf, voidpf stream) { return static_cast<Memory*>(stream)->at; }
long ZCALLBACK seek_memory(voidpf, voidpf stream, ZPOS64_T offset, int origin) {
  auto& m = *static_cast<Memory*>(stream);
  const std::size_t base = origin == ZLIB_FILEFUNC_SEEK_SET ? 0 : origin == ZLIB_FILEFUNC_SEEK_CUR ? m.at : m.bytes.size();
  m.at = base + offset;
  return 0;
}
int ZCALLBACK close_memory(voidpf, voidpf) { return 0; }
int ZCALLBACK error_memory(voidpf, voidpf) { return 0; }

void check(int status, const char* what, const std::string& name) {
  if (status != ZIP_OK) throw std::runtime_error(fmt::format("minizip: {} of '{}' failed (status {})", what, name, status));
}

}  // namespace

std::string zip_archive(const std::vector<ArchiveEntry>& entries) {
  Memory memory;
  zlib_filefunc64_def functions{open_memory, read_memory, write_memory, tell_memory, seek_memory, close_memory, error_memory, &memory};
  zipFile zip = zipOpen2_64("memory", APPEND_STATUS_CREATE, nullptr, &functions);
  if (!zip) throw std::runtime_error("minizip: cannot open an archive in memory");
  for (const auto& e : entries) {
    if (e.bytes.size() > std::numeric_limits<unsigned>::max()) {
      zipClose(zip, nullptr);
      throw std::runtime_error(fmt::format("'{}' is larger than a ZIP entry without zip64 holds", e.name));
    }
    zip_fileinfo info{};
    info.tmz_date = {0, 0, 0, 1, 0, 1980};  // 1980-01-01 00:00:00
    const bool folder = !e.name.empty() && e.name.back() == '/';
    int status = zipOpenNewFileInZip64(zip, e.name.c_str(), &info, nullptr, 0, nullptr, 0, nullptr, folder ? 0 : Z_DEFLATED,
                                       folder ? 0 : Z_BEST_COMPRESSION, 0);
    if (status == ZIP_OK && !e.bytes.empty()) status = zipWriteInFileInZip(zip, e.bytes.data(), static_cast<unsigned>(e.bytes.size()));
    if (status == ZIP_OK) status = zipCloseFileInZip(zip);
    if (status != ZIP_OK) zipClose(zip, nullptr);
    check(status, "writing", e.name);
  }
  check(zipClose(zip, nullptr), "closing", "the archive");
  return std::move(memory.bytes);
}

}  // namespace rheo::runtime::exporter
