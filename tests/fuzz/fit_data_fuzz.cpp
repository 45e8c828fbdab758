// libFuzzer target: the input is a fit's measured-data file (runtime/io/fit_data.hpp), read by
// read_fit_data itself, which takes only a path: each input is written to an in-memory file of
// this process (memfd) and read back through /proc/self/fd, so nothing touches the disk.
#include "documented_errors.hpp"
#include "runtime/io/fit_data.hpp"

#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

int scratch_fd() {
  static const int fd = memfd_create("rheo_fit_data_fuzz.csv", 0);
  if (fd < 0) {
    std::perror("rheo fuzz: memfd_create");
    std::abort();
  }
  return fd;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const int fd = scratch_fd();
  if (ftruncate(fd, 0) != 0 || pwrite(fd, data, size, 0) != static_cast<ssize_t>(size)) {
    std::perror("rheo fuzz: cannot write the in-memory file");
    std::abort();
  }
  const std::string path = "/proc/self/fd/" + std::to_string(fd);
  rheo::fuzz::expect_only_documented_errors([&] { (void)rheo::runtime::read_fit_data(path, 1.0); });
  return 0;
}
