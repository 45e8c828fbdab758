// Whole-file reads with a size bound: a stray `/dev/zero`, a FIFO that never ends or a
// multi-gigabyte log given by mistake must fail with a message, not exhaust memory.
#pragma once

#include <cstddef>
#include <string>

namespace rheo::lang {

struct FileText {
  std::string text;     // the file's bytes when `failure` is empty
  std::string failure;  // why it could not be read: "it is a directory", the errno text, or
                        // "it is larger than N MiB, the most rheo reads"
  // What to do about `failure`: "check the path", or for a file past the bound "is it the
  // right file?".
  const char* advice() const;
};

// Reads PATH, at most MAX_BYTES of it. Never throws for the file's sake (std::bad_alloc aside).
FileText read_file_text(const std::string& path, std::size_t max_bytes);

}  // namespace rheo::lang
