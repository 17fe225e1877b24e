#include "common/output_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>
#include <utility>

#include "common/input_error.hpp"

namespace rtmot {

OutputFile::OutputFile(std::filesystem::path path, Publish publish, std::size_t buffer_bytes)
    : path_(std::move(path)), publish_(publish), buffer_(std::max<std::size_t>(buffer_bytes, 1)) {
  written_path_ = publish_ == Publish::on_close
                      ? std::filesystem::path(path_.string() + ".tmp-" + std::to_string(::getpid()))
                      : path_;
  fd_ = ::open(written_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd_ < 0) {
    const int error = errno;
    throw InputError(path_.string(), 0, "", std::string("cannot create: ") + std::strerror(error));
  }
}

OutputFile::~OutputFile() {
  if (fd_ < 0) return;  // closed or moved from
  if (publish_ == Publish::as_written) {
    try {
      flush();
    } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor cannot report; close() does
    }
  } else {
    ::unlink(written_path_.c_str());
  }
  if (fd_ >= 0) ::close(fd_);
}

OutputFile::OutputFile(OutputFile&& other) noexcept
    : path_(std::move(other.path_)),
      written_path_(std::move(other.written_path_)),
      publish_(other.publish_),
      fd_(std::exchange(other.fd_, -1)),
      whole_bytes_(other.whole_bytes_),
      buffer_(std::move(other.buffer_)),
      used_(std::exchange(other.used_, 0)) {}

void OutputFile::write(const void* data, std::size_t size) {
  if (fd_ < 0) throw InputError(path_.string(), 0, "", "write after close");
  if (used_ + size > buffer_.size()) flush();
  if (size > buffer_.size()) {
    write_out(static_cast<const char*>(data), size);  // alone: still one record, one write()
    return;
  }
  std::memcpy(buffer_.data() + used_, data, size);
  used_ += size;
}

void OutputFile::flush() {
  if (fd_ < 0 || used_ == 0) return;
  const std::size_t size = used_;
  used_ = 0;
  write_out(buffer_.data(), size);
}

void OutputFile::write_out(const char* data, std::size_t size) {
  std::size_t done = 0;
  while (done < size) {
    const ssize_t wrote = ::write(fd_, data + done, size - done);
    if (wrote < 0 && errno == EINTR) continue;
    if (wrote <= 0) {
      const int error = wrote < 0 ? errno : ENOSPC;
      // Cut back to the last whole record, so that what stays readable is whole.
      if (::ftruncate(fd_, static_cast<off_t>(whole_bytes_)) == 0) {
        ::lseek(fd_, static_cast<off_t>(whole_bytes_), SEEK_SET);
      }
      fail("cannot write", error);
    }
    done += static_cast<std::size_t>(wrote);
  }
  whole_bytes_ += size;
}

void OutputFile::close() {
  if (fd_ < 0) return;
  flush();
  // A published file must be on the disk before its name is: a crash after the rename must not
  // leave an empty file under the final name.
  if (publish_ == Publish::on_close && ::fsync(fd_) != 0) fail("cannot write", errno);
  const int fd = std::exchange(fd_, -1);
  if (::close(fd) != 0) {
    const int error = errno;
    if (publish_ == Publish::on_close) ::unlink(written_path_.c_str());
    throw InputError(path_.string(), 0, "", std::string("cannot write: ") + std::strerror(error),
                     ExitCode::io_error);
  }
  if (publish_ == Publish::on_close && ::rename(written_path_.c_str(), path_.c_str()) != 0) {
    const int error = errno;
    ::unlink(written_path_.c_str());
    throw InputError(path_.string(), 0, "", std::string("cannot rename: ") + std::strerror(error),
                     ExitCode::io_error);
  }
}

void OutputFile::fail(const char* action, int error) {
  throw InputError(path_.string(), 0, "", std::string(action) + ": " + std::strerror(error),
                   ExitCode::io_error);
}

void write_whole_file(const std::filesystem::path& path, std::string_view text) {
  OutputFile file(path, OutputFile::Publish::on_close, 0);
  file.write(text);
  file.close();
}

}  // namespace rtmot
