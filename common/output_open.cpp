#include "common/output_open.hpp"

#include <fcntl.h>
#include <spdlog/spdlog.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "common/input_error.hpp"
#include "common/stale_temporaries.hpp"

namespace rtmot {
namespace {

[[noreturn]] void refuse(const std::filesystem::path& path, const std::string& why) {
  throw InputError(path.string(), 0, "", why);
}

[[noreturn]] void refuse_errno(const std::filesystem::path& path, const char* action, int error) {
  refuse(path, std::string(action) + ": " + std::strerror(error));
}

// What open() failing with `error` on PATH means, where rtmot can say more than strerror.
[[noreturn]] void refuse_open(const std::filesystem::path& path, int error) {
  struct stat status {};
  if (error == ENXIO && ::stat(path.c_str(), &status) == 0) {
    if (S_ISFIFO(status.st_mode)) {
      refuse(path,
             "is a FIFO with no reader: nothing would read what is written (start its "
             "reader first)");
    }
    if (S_ISSOCK(status.st_mode)) refuse(path, "is a socket, not a file to write");
  }
  if (error == EISDIR) refuse(path, "is a folder, not a file to write");
  refuse_errno(path, "cannot create", error);
}

}  // namespace

int open_output_in_place(const std::filesystem::path& path, OutputMode mode) {
  // O_NONBLOCK: a FIFO without a reader fails with ENXIO instead of blocking in open(); not
  // O_TRUNC: a file is emptied only once its lock is held, so a second writer empties nothing.
  const int flags =
      O_WRONLY | O_CREAT | O_CLOEXEC | O_NONBLOCK | (mode == OutputMode::append ? O_APPEND : 0);
  int fd = -1;
  do {
    fd = ::open(path.c_str(), flags, 0666);
  } while (fd < 0 && errno == EINTR);
  if (fd < 0) refuse_open(path, errno);
  const auto close_and_refuse = [&](const std::string& why) {
    ::close(fd);
    refuse(path, why);
  };
  struct stat status {};
  if (::fstat(fd, &status) != 0)
    close_and_refuse(std::string("cannot stat: ") + std::strerror(errno));
  if (S_ISBLK(status.st_mode)) close_and_refuse("is a block device, not a file to write");
  // Writes block as usual (a FIFO's reader that is slow is waited for).
  if (::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK) != 0) {
    close_and_refuse(std::string("cannot write: ") + std::strerror(errno));
  }
  if (!S_ISREG(status.st_mode) || mode == OutputMode::append) return fd;
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    if (error == EWOULDBLOCK) {
      close_and_refuse(
          "is being written by another process (it holds the file's lock): two "
          "writers would interleave their records");
    }
    // A file system without locks (some network mounts) is written unlocked, as before.
    if (error != ENOLCK && error != EOPNOTSUPP && error != EINVAL) {
      close_and_refuse(std::string("cannot lock: ") + std::strerror(error));
    }
  }
  if (::ftruncate(fd, 0) != 0)
    close_and_refuse(std::string("cannot empty: ") + std::strerror(errno));
  return fd;
}

int create_temporary(const std::filesystem::path& path) {
  remove_stale_temporaries(path);
  const std::filesystem::path temporary = temporary_path_for(path);
  constexpr int kFlags = O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC;
  for (int attempt = 0;; ++attempt) {
    const int fd = ::open(temporary.c_str(), kFlags, 0666);
    if (fd >= 0) return fd;
    const int error = errno;
    if (error == EINTR) continue;
    // Named by the user's PATH: the temporary is ours (a missing folder, no permission).
    if (error != EEXIST || attempt > 0) refuse_errno(path, "cannot create", error);
    struct stat status {};
    if (::lstat(temporary.c_str(), &status) != 0) continue;  // gone meanwhile: try again
    if (S_ISDIR(status.st_mode)) {
      refuse(temporary, "is a folder where rtmot writes " + path.filename().string() +
                            " before publishing it: remove it");
    }
    if (::unlink(temporary.c_str()) != 0) refuse_errno(temporary, "cannot remove", errno);
    spdlog::warn(
        "{}: removed {} found under the name of this process's temporary (a leftover "
        "of an earlier process with the same id, or planted): never written through",
        temporary.string(), S_ISLNK(status.st_mode) ? "a symbolic link" : "a file");
  }
}

}  // namespace rtmot
