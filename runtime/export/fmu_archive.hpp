// A ZIP archive built in memory (the container of an FMU, FMI 2.0 section 2.3), with Debian's
// minizip: entries deflated, dated 1980-01-01 (the format's epoch, so that the same export gives
// the same bytes), folders as entries of their own ending in '/'.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace rheo::runtime::exporter {

struct ArchiveEntry {
  std::string name;  // "resources/model.rheo", or a folder "resources/"
  std::string_view bytes;
};

// The bytes of a ZIP archive holding ENTRIES in order. std::runtime_error when minizip fails
// (it writes to memory here, so only when memory runs out).
std::string zip_archive(const std::vector<ArchiveEntry>& entries);

}  // namespace rheo::runtime::exporter
