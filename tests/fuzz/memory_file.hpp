#pragma once
// The MOTChallenge readers take a path. Rather than add an in-memory entry point to them for the
// fuzzer, the input is written to an anonymous in-memory file (memfd) and read back by its
// /proc/self/fd path: the readers are exercised exactly as in production, and nothing touches disk.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

namespace rtmot::fuzz {

class MemoryFile {
 public:
  MemoryFile() : fd_(memfd_create("rtmot-fuzz", 0)) {
    if (fd_ < 0) std::abort();  // the harness cannot run at all: not a finding
  }
  ~MemoryFile() { close(fd_); }
  MemoryFile(const MemoryFile&) = delete;
  MemoryFile& operator=(const MemoryFile&) = delete;

  /// Replaces the content with `data` and returns a path that opens it.
  std::string write(const std::uint8_t* data, std::size_t size) {
    if (ftruncate(fd_, 0) != 0) std::abort();
    std::size_t done = 0;
    while (done < size) {
      const ssize_t n = pwrite(fd_, data + done, size - done, static_cast<off_t>(done));
      if (n <= 0) std::abort();
      done += static_cast<std::size_t>(n);
    }
    return "/proc/self/fd/" + std::to_string(fd_);
  }

 private:
  int fd_;
};

}  // namespace rtmot::fuzz
