#include "runtime/io/output_file.hpp"

#include "runtime/core/errors.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <iostream>

namespace rheo::runtime {

namespace fs = std::filesystem;

fs::path link_target(const std::string& path) {
  fs::path target(path);
  std::error_code link_error;
  for (int depth = 0; fs::is_symlink(fs::symlink_status(target, link_error)); ++depth) {
    const fs::path next = fs::read_symlink(target, link_error);
    if (link_error || depth == 40)
      throw DataError(fmt::format("{}: error: cannot follow the link ({}); write to its target instead", path,
                                  link_error ? link_error.message() : "too many levels of links"));
    target = next.is_absolute() ? next : target.parent_path() / next;
  }
  return target;
}

namespace {

bool is_device_or_pipe(const fs::path& target) {
  std::error_code status_error;
  const auto status = fs::status(target, status_error);
  return fs::exists(status) && !fs::is_regular_file(status);
}

// Copies FROM (from its start) to TO; false when a read or a write failed.
bool copy_all(std::FILE* from, std::FILE* to) {
  std::rewind(from);
  char chunk[1 << 16];
  for (std::size_t got; (got = std::fread(chunk, 1, sizeof chunk, from)) > 0;)
    if (std::fwrite(chunk, 1, got, to) != got) return false;
  return !std::ferror(from);
}

}  // namespace

fs::path temporary_beside(const fs::path& target) {
  static std::atomic<unsigned> count{0};
  return target.parent_path() / fmt::format(".{}.rheo-tmp-{}-{}", target.filename().string(), ::getpid(), count++);
}

void check_output_destination(const std::string& path) {
  if (path.empty() || path == "-") return;
  const fs::path target(path);
  std::error_code ec;
  if (fs::is_directory(target, ec))
    throw DataError(fmt::format("{}: error: the output is a directory; name a file in it, e.g. {}", path, (target / "result.csv").string()));
  const fs::path parent = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  if (!fs::is_directory(parent, ec))
    throw DataError(fmt::format("{}: error: the output's directory {} does not exist; create it or choose another path", path, parent.string()));
  // write_output writes a device or pipe in place, and a regular file (through its links) to a
  // temporary sibling renamed over it: the first needs the file writable, the second its directory.
  const auto status = fs::status(target, ec);
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    if (::access(target.c_str(), W_OK) != 0)
      throw DataError(fmt::format("{}: error: the output cannot be written ({}); choose another path", path, std::strerror(errno)));
    return;
  }
  const fs::path resolved = fs::exists(status) ? fs::canonical(target, ec) : target;
  const fs::path directory = ec || resolved.parent_path().empty() ? parent : resolved.parent_path();
  if (::access(directory.c_str(), W_OK | X_OK) != 0)
    throw DataError(fmt::format("{}: error: the output's directory {} is not writable ({}); choose another path", path, directory.string(),
                                std::strerror(errno)));
}

void write_output(const std::string& path, const std::string& content) {
  if (path.empty() || path == "-") {
    std::cout << content << std::flush;
    return;
  }
  check_output_destination(path);
  const fs::path target = link_target(path);
  if (is_device_or_pipe(target)) {
    // A device or pipe (/dev/null, a FIFO): write in place; renaming over it would replace it.
    std::FILE* stream = std::fopen(target.c_str(), "wb");
    const bool ok = stream && std::fwrite(content.data(), 1, content.size(), stream) == content.size();
    if (stream) std::fclose(stream);
    if (!ok) throw DataError(fmt::format("{}: error: cannot write output ({})", path, std::strerror(errno)));
    return;
  }
  const fs::path temporary = temporary_beside(target);
  std::FILE* file = std::fopen(temporary.c_str(), "wb");
  if (!file)
    throw DataError(fmt::format("{}: error: cannot write output ({}); check that the directory exists and is writable", path, std::strerror(errno)));
  const bool written = std::fwrite(content.data(), 1, content.size(), file) == content.size();
  const bool closed = std::fclose(file) == 0;
  std::error_code ec;
  if (!written || !closed) {
    fs::remove(temporary, ec);
    throw DataError(fmt::format("{}: error: writing the output failed (disk full?); nothing was written", path));
  }
  fs::rename(temporary, target, ec);
  if (ec) {
    fs::remove(temporary, ec);
    throw DataError(fmt::format("{}: error: cannot replace the output file ({})", path, ec.message()));
  }
}

PendingOutput::PendingOutput(const std::string& path, Temporary temporary) : path_(path), link_unnamed_(temporary == Temporary::best) {
  const bool standard = path.empty() || path == "-";
  if (!standard) {
    check_output_destination(path);
    const fs::path target = link_target(path);
    if (!is_device_or_pipe(target)) target_ = target;
  }
  if (target_.empty()) {
    file_ = std::tmpfile();  // unnamed: the system removes it however the process ends
    if (!file_)
      throw DataError(fmt::format("{}: error: cannot make a temporary file for the output ({})", standard ? "-" : path, std::strerror(errno)));
    return;
  }
  temporary_ = temporary_beside(target_);
  // Unnamed in the target's directory where the file system allows (O_TMPFILE): even a killed
  // run leaves nothing; it is named temporary_ at commit, then renamed over the target. Open
  // for reading too: naming it may copy it. A file system without O_TMPFILE fails the open
  // (EOPNOTSUPP, or EISDIR on kernels before 3.11): a named sibling then.
  const fs::path directory = target_.parent_path().empty() ? fs::path(".") : target_.parent_path();
  if (temporary != Temporary::named_sibling)
    if (const int fd = ::open(directory.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0666); fd >= 0) {
      file_ = ::fdopen(fd, "w+b");
      if (!file_) ::close(fd);
      unnamed_ = file_ != nullptr;
    }
  if (!file_) file_ = std::fopen(temporary_.c_str(), "wb");
  if (!file_)
    throw DataError(fmt::format("{}: error: cannot write output ({}); check that the directory exists and is writable", path, std::strerror(errno)));
}

PendingOutput::~PendingOutput() {
  if (file_) std::fclose(file_);
  std::error_code ec;
  if (!committed_ && !unnamed_ && !temporary_.empty()) fs::remove(temporary_, ec);
}

void PendingOutput::failed_write() {
  throw DataError(
      fmt::format("{}: error: writing the output failed ({}; disk full?); nothing was written", path_.empty() ? "-" : path_, std::strerror(errno)));
}

void PendingOutput::write(std::string_view bytes) {
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) failed_write();
}

void PendingOutput::restart() {
  if (std::fflush(file_) != 0 || ::ftruncate(::fileno(file_), 0) != 0) failed_write();
  std::rewind(file_);
}

void PendingOutput::commit() {
  if (committed_) throw std::logic_error("PendingOutput committed twice");
  if (std::fflush(file_) != 0) failed_write();
  if (temporary_.empty()) {  // spooled: copied to standard output, the device or the pipe
    const bool standard = path_.empty() || path_ == "-";
    std::FILE* out = standard ? stdout : std::fopen(link_target(path_).c_str(), "wb");
    if (!out) throw DataError(fmt::format("{}: error: cannot write output ({})", path_, std::strerror(errno)));
    if (standard) std::cout << std::flush;
    bool ok = copy_all(file_, out) && std::fflush(out) == 0;
    if (!standard) ok = std::fclose(out) == 0 && ok;
    committed_ = true;
    if (!ok) throw DataError(fmt::format("{}: error: cannot write output ({})", standard ? "-" : path_, std::strerror(errno)));
    return;
  }
  if (unnamed_) name_temporary();
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  std::error_code ec;
  if (!closed) {
    fs::remove(temporary_, ec);
    throw DataError(fmt::format("{}: error: writing the output failed (disk full?); nothing was written", path_));
  }
  fs::rename(temporary_, target_, ec);
  if (ec) {
    fs::remove(temporary_, ec);
    throw DataError(fmt::format("{}: error: cannot replace the output file ({})", path_, ec.message()));
  }
  committed_ = true;
}

// The unnamed file gets the name temporary_ (linkat through /proc/self/fd), or, where that
// fails (no /proc), its content is copied to a new file of that name.
void PendingOutput::name_temporary() {
  const std::string self = fmt::format("/proc/self/fd/{}", ::fileno(file_));
  unnamed_ = false;
  if (link_unnamed_ && ::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, temporary_.c_str(), AT_SYMLINK_FOLLOW) == 0) return;
  std::FILE* named = std::fopen(temporary_.c_str(), "wb");
  const bool ok = named && copy_all(file_, named);
  if (named && std::fclose(named) != 0 && ok) failed_write();
  if (!ok) failed_write();
}

}  // namespace rheo::runtime
