#include "common/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <utility>

#include "common/input_error.hpp"

namespace rtmot {
namespace {

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO (pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  return "not a regular file";
}

}  // namespace

InputFile::InputFile(std::filesystem::path path, std::uint64_t max_bytes) : path_(std::move(path)) {
  // O_NONBLOCK: opening a FIFO without a writer would block; it is refused below anyway.
  fd_ = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd_ < 0) {
    const int error = errno;
    throw InputError(path_.string(), 0, "",
                     error == ENOENT ? "cannot open file: no such file"
                                     : std::string("cannot open file: ") + std::strerror(error));
  }
  struct stat status {};
  if (::fstat(fd_, &status) != 0) {
    const int error = errno;
    ::close(fd_);
    throw InputError(path_.string(), 0, "", std::string("cannot stat: ") + std::strerror(error),
                     ExitCode::io_error);
  }
  if (!S_ISREG(status.st_mode)) {
    ::close(fd_);
    throw InputError(path_.string(), 0, "",
                     std::string("is ") + kind_of(status.st_mode) + ", expected a regular file");
  }
  size_ = static_cast<std::uint64_t>(status.st_size);
  if (size_ > max_bytes) {
    ::close(fd_);
    throw InputError(path_.string(), 0, "",
                     "is " + std::to_string(size_) + " bytes, more than the limit of " +
                         std::to_string(max_bytes));
  }
}

InputFile::~InputFile() {
  if (fd_ >= 0) ::close(fd_);
}

InputFile::InputFile(InputFile&& other) noexcept
    : path_(std::move(other.path_)), fd_(std::exchange(other.fd_, -1)), size_(other.size_) {}

InputFile& InputFile::operator=(InputFile&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    path_ = std::move(other.path_);
    fd_ = std::exchange(other.fd_, -1);
    size_ = other.size_;
  }
  return *this;
}

std::size_t InputFile::read(void* data, std::size_t size) {
  auto* const bytes = static_cast<char*>(data);
  std::size_t total = 0;
  while (total < size) {
    const ssize_t got = ::read(fd_, bytes + total, size - total);
    if (got == 0) break;
    if (got < 0) {
      if (errno == EINTR) continue;
      throw InputError(path_.string(), 0, "", std::string("read error: ") + std::strerror(errno),
                       ExitCode::io_error);
    }
    total += static_cast<std::size_t>(got);
  }
  return total;
}

void InputFile::skip(std::uint64_t bytes) {
  if (::lseek(fd_, static_cast<off_t>(bytes), SEEK_CUR) < 0) {
    throw InputError(path_.string(), 0, "", std::string("cannot seek: ") + std::strerror(errno),
                     ExitCode::io_error);
  }
}

std::string input_file_problem(const std::filesystem::path& path) {
  try {
    const InputFile file(path);
  } catch (const InputError& error) {
    return error.problem();
  }
  return {};
}

std::string read_text_file(const std::filesystem::path& path, std::uint64_t max_bytes) {
  InputFile file(path, max_bytes);
  std::string text;
  text.resize(static_cast<std::size_t>(file.size()) + 1);  // + 1: sees a file that grew
  std::size_t used = 0;
  while (true) {
    used += file.read(text.data() + used, text.size() - used);
    if (used < text.size()) break;  // the end
    if (used > max_bytes) {
      throw InputError(path.string(), 0, "",
                       "grew beyond the limit of " + std::to_string(max_bytes) + " bytes");
    }
    text.resize(std::min<std::uint64_t>(text.size() * 2, max_bytes + 1));
  }
  text.resize(used);
  return text;
}

}  // namespace rtmot
