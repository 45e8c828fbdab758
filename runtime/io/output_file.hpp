// Writing outputs so that a failed run never leaves a half-written file and earlier outputs
// stay intact: a file is written to a temporary sibling and renamed over its destination when
// whole. A symbolic link is written through to its target and stays a link. Devices and pipes
// (/dev/null, FIFOs) are written in place by write_output(); a PendingOutput spools them.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

namespace rheo::runtime {

// PATH with its symbolic links followed, as the kernel would, to a depth of 40: the file that
// is written (created if missing). DataError when a link cannot be followed.
std::filesystem::path link_target(const std::string& path);
// A temporary sibling of TARGET, unique in this process: ".NAME.rheo-tmp-PID-N".
std::filesystem::path temporary_beside(const std::filesystem::path& target);

// Writes `content` to `path` atomically ("-" or empty: standard output). Throws DataError.
void write_output(const std::string& path, const std::string& content);

// DataError unless `path` ("-" or empty: standard output) can be written: a directory, a
// parent directory that does not exist or is not writable, or a device or pipe that is not, is
// named with advice. Called before long runs, so
// that a fit does not end with its result unwritable.
void check_output_destination(const std::string& path);

// An output written as it is made (a streamed history, in constant memory) and put in place
// only by commit(): a regular file (new or not, through its links) goes to a temporary file in
// its directory, unnamed until commit() names it and renames it over the file (a sibling named
// from the start where the file system has no O_TMPFILE); standard output ("-" or empty), a
// device or a pipe gets an unnamed temporary file (in the system's temporary directory) copied
// to it. Destroyed without commit(), it leaves nothing behind; killed, nothing but a named
// sibling where O_TMPFILE is missing. DataError where the output cannot be opened or written
// (disk full).
class PendingOutput {
 public:
  // How a regular file's temporary is made. The default takes the best the system offers and
  // falls back by itself (no O_TMPFILE: a named sibling; no /proc to name an unnamed file: its
  // content copied to the sibling at commit); tests force each fallback.
  enum class Temporary { best, unnamed_copied_at_commit, named_sibling };

  explicit PendingOutput(const std::string& path, Temporary temporary = Temporary::best);
  ~PendingOutput();
  PendingOutput(const PendingOutput&) = delete;
  PendingOutput& operator=(const PendingOutput&) = delete;

  void write(std::string_view bytes);
  // Forgets what was written.
  void restart();
  // Puts the output in place. Once.
  void commit();

 private:
  [[noreturn]] void failed_write();
  void name_temporary();

  std::string path_;                 // as given, for messages
  std::filesystem::path target_;     // the file renamed over (links followed); empty when spooled
  std::filesystem::path temporary_;  // the sibling written; empty when spooled
  std::FILE* file_ = nullptr;
  bool unnamed_ = false;      // file_ is an O_TMPFILE file, temporary_ not yet its name
  bool link_unnamed_ = true;  // name it through /proc/self/fd (else by copying it)
  bool committed_ = false;
};

}  // namespace rheo::runtime
